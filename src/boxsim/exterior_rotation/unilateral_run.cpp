#include "boxsim/exterior_rotation/unilateral_run.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/collision/contact_manifold.hpp"
#include "boxsim/collision/obb.hpp"

namespace boxsim {

namespace {

/// The signed depth of bodies a and b (UnilateralSample::hingeDepth): the narrow phase's depth
/// with a margin wide enough to see them 5 cm apart.
double signedDepth(const World& world, int a, int b) {
  const ContactManifold m = collideBoxes(Obb::of(world.bodies[static_cast<std::size_t>(a)]),
                                         Obb::of(world.bodies[static_cast<std::size_t>(b)]), 0.05);
  return m.depth;
}

UnilateralSample sample(const StickingScene& scene, const World& world, double t) {
  UnilateralSample s;
  s.t = t;
  s.penetration = deepestPenetration(world);
  for (const int pivot : scene.pivots) {
    const StickingContact& c = scene.contacts[static_cast<std::size_t>(pivot)];
    s.hingeDepth.push_back(signedDepth(world, c.a, c.b));
  }
  return s;
}

}  // namespace

UnilateralRun runUnilateral(const StickingScene& scene, double dt, int steps, const UnilateralParams& params) {
  if (steps < 1) throw std::invalid_argument("runUnilateral needs at least one step");
  if (!(dt > 0.0) || !std::isfinite(dt))
    throw std::invalid_argument("runUnilateral: dt must be positive and finite");
  UnilateralRun run;
  run.end = scene.world;
  World& world = run.end;
  run.samples.push_back(sample(scene, world, 0.0));
  const AnalyticStepper forces(params.analytic);
  for (int step = 1; step <= steps; ++step) {
    // The forces of this instant (Baraff's LCP, §3.3.1's ε and clamp), held over the step.
    integrateWorld(world, dt, params.integrator, {}, forces.contactWrenches(world, dt));
    run.samples.push_back(sample(scene, world, step * dt));
    run.maxPenetration = std::max(run.maxPenetration, run.samples.back().penetration);
  }
  return run;
}

}  // namespace boxsim
