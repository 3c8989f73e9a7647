/// \file
/// gatherCollisions at predicted positions (\alg{A.2}), every pass or once per step.
#include "boxsim/impulse_damped/contact_gathering.hpp"

#include <cmath>
#include <stdexcept>

#include "boxsim/collision/broad_phase.hpp"

namespace boxsim {

ContactGathering::ContactGathering(const ImpulseParams& params)
    : params_(params), normals_(params.normalModel), once_(params) {
  if (!(params.exactReach >= 0.0) || !std::isfinite(params.exactReach) ||
      !(params.slowWidening >= params.exactReach) || !std::isfinite(params.slowWidening))
    throw std::invalid_argument(
        "contact gathering: the exact reach must be a finite number >= 0 and the widening a "
        "finite number >= the exact reach (units of l)");
  if (params.integrator != Integrator::SemiImplicitEuler &&
      params.integrator != Integrator::SplitRotation)
    throw std::invalid_argument("the impulse-based step integrates with semi_implicit_euler or "
                                "split_rotation (its velocities come before its positions), not " +
                                integratorName(params.integrator));
}

std::vector<ImpulseContact>& ContactGathering::begin(World& world, double dt, GravityMode predict,
                                                     double margin) {
  const Vec3 gravityStep = gravityVelocity(world, predict, dt);
  if (params_.gathering == ContactGatheringMode::EveryPass) {
    // RESOLVECOLLISIONS L2-L3, RESOLVECONTACTS L2-L3: integrateObjectPositions, remembering
    // where every body was, then gatherCollisions.
    const SavedPoses saved = predictPositions(world, dt, gravityStep);
    contacts_ = normals_.contactsOf(world, findContacts(world, margin));
    // DEVIATION(RESOLVECOLLISIONS L6, RESOLVECONTACTS L6): revertToOriginalPositions comes
    // before COLLIDE (the file comment, "Where COLLIDE acts").
    revertPositions(world, saved);
  } else {
    once_.gather(world, gravityStep, dt, margin, normals_, contacts_);
  }
  if (!params_.commonLeverPoint) return contacts_;
  // ImpulseParams::commonLeverPoint: both impulses act at one point, the midpoint of the
  // material points x + r' the found lever arms name at the current poses, so ±J exert no net
  // torque about any fixed point.
  for (ImpulseContact& c : contacts_) {
    const Vec3& xa = world.bodies[c.a].s.x;
    const Vec3& xb = world.bodies[c.b].s.x;
    const Vec3 q = 0.5 * ((xa + c.ra) + (xb + c.rb));
    c.ra = q - xa;
    c.rb = q - xb;
  }
  return contacts_;
}

void ContactGathering::beginStep(const World& world, double dt, GravityMode predict,
                                 double margin) {
  if (params_.gathering != ContactGatheringMode::OncePerStep) return;
  once_.beginStep(world, gravityVelocity(world, predict, dt), dt, margin, normals_);
}

void ContactGathering::end(World&) {
  // revertToOriginalPositions (RESOLVECOLLISIONS L6, RESOLVECONTACTS L6) already happened in
  // begin(); the momenta the impulses
  // changed stay.
  once_.endPass();
}

void ContactGathering::endStep() {
  normals_.endStep();
  once_.endStep();
}

bool ContactGathering::stepPairs(const World& world, double margin,
                                 std::vector<std::pair<int, int>>& pairs) const {
  if (params_.gathering != ContactGatheringMode::OncePerStep) return false;
  return once_.stepPairs(world, margin, pairs);
}

std::string contactGatheringName(ContactGatheringMode mode) {
  return enumName(kContactGatheringNames, mode);
}

ContactGatheringMode parseContactGathering(const std::string& name) {
  return parseEnum(kContactGatheringNames, name, "contact gathering");
}

}  // namespace boxsim
