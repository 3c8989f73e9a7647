// Verification of the exterior rotation measurement (thesis §6.2, Figs. 6.1-6.3): the reduced
// reference, the sticking contact forces against it, the order at which each integrator's
// contact drift shrinks with dt (forward Euler, the footnote's Runge-Kutta in both forms, the
// screw update), the projection's bound, the physical validity of sticking over each window,
// the sign conventions of the measures, determinism and bad input.
#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/exterior_rotation/sticking_run.hpp"
#include "boxsim/exterior_rotation/unilateral_run.hpp"

using namespace boxsim;

namespace {

int stepsOf(const StickingScene& scene, double dt) { return static_cast<int>(std::lround(scene.window / dt)); }

/// The largest |p_b - p_a| over the window for each dt.
std::vector<double> maxErrors(const StickingScene& scene, StickingMethod method, const std::vector<double>& dts) {
  std::vector<double> errors;
  for (const double dt : dts) errors.push_back(runSticking(scene, method, dt, stepsOf(scene, dt)).summary.maxError);
  return errors;
}

/// dt0 and four halvings.
std::vector<double> halvings(double dt0) {
  std::vector<double> dts;
  for (int k = 0; k < 5; ++k) dts.push_back(dt0 / std::pow(2.0, k));
  return dts;
}

/// m g L of a scene: the scale of its energy, J (total movable mass, g, 0.5 m).
double energyScale(const StickingScene& scene) {
  double mass = 0.0;
  for (const RigidBody& b : scene.world.bodies)
    if (!b.immovable) mass += b.mass;
  return mass * scene.world.gravity.norm() * 0.5;
}

}  // namespace

TEST_CASE("The hinge reference conserves energy to 1e-10 of m g L over each window", "[exterior_rotation][reference]") {
  for (const StickingScene& scene : allStickingScenes()) {
    INFO(scene.name);
    HingeReference reference(scene);
    const double e0 = reference.energy();
    double worst = 0.0;
    for (int i = 1; i <= 100; ++i) {
      reference.advanceTo(scene.window * i / 100.0);
      worst = std::max(worst, std::abs(reference.energy() - e0));
    }
    // rk8pd at 1e-12 per step leaves ~1e-13 J; 1e-10 m g L is a thousand times that.
    CHECK(worst < 1e-10 * energyScale(scene));
    // and the motion is a real rotation: 30-60 degrees of the first link.
    const double turned = -reference.angles()[0] * 180.0 / kPi;
    CHECK((scene.name == "two_frames" ? turned > 15.0 : turned > 30.0));
    CHECK(turned < 60.0);
  }
}

TEST_CASE("The sticking solve leaves no relative acceleration at any contact point", "[exterior_rotation][invariant]") {
  for (const StickingScene& scene : allStickingScenes()) {
    INFO(scene.name);
    // Along the reference, where velocities and so the centripetal terms are non-zero.
    HingeReference reference(scene);
    reference.advanceTo(0.8 * scene.window);
    World world = scene.world;
    reference.applyTo(world);
    const StickingSolution f = solveStickingForces(world, scene.points, static_cast<int>(scene.contacts.size()));
    // Recomputed here from the solution's accelerations, not taken from the solver's residual.
    for (const PointConstraint& p : scene.points) {
      const auto pointAcceleration = [&](int k, const Vec3& rLocal) {
        const RigidBody& b = world.bodies[k];
        const Vec3 r = b.R * rLocal;
        return Vec3(f.a[k] + f.alpha[k].cross(r) + b.omega.cross(b.omega.cross(r)));
      };
      const Vec3 relative = pointAcceleration(p.b, p.rB) - pointAcceleration(p.a, p.rA);
      // Rounding of a solve whose right side is ~g: 1e-10 m/s^2 is 1e5 ulp of g.
      CHECK(relative.norm() < 1e-10);
    }
    // The redundant points leave exactly one degree of freedom per hinge.
    CHECK(f.rank == 6 * scene.world.movableCount() - static_cast<int>(scene.links.size()));
  }
}

TEST_CASE("The sticking solve gives the reference's angular accelerations at t = 0 and along the motion",
          "[exterior_rotation][reference]") {
  for (const StickingScene& scene : allStickingScenes()) {
    INFO(scene.name);
    HingeReference reference(scene);
    for (const double fraction : {0.0, 0.5, 1.0}) {
      reference.advanceTo(fraction * scene.window);
      World world = scene.world;
      reference.applyTo(world);
      const StickingSolution f = solveStickingForces(world, scene.points, static_cast<int>(scene.contacts.size()));
      const Eigen::VectorXd phiDDot = reference.angularAccelerations();
      for (std::size_t k = 0; k < scene.links.size(); ++k)
        for (const int b : scene.links[k].bodies) {
          CHECK(f.alpha[b].z() == Approx(phiDDot[k]).epsilon(1e-9));
          CHECK(std::abs(f.alpha[b].x()) + std::abs(f.alpha[b].y()) < 1e-9);
        }
    }
  }
}

TEST_CASE("Every pivot stays compressive, above a quarter of its initial load, over each window",
          "[exterior_rotation][invariant]") {
  for (const StickingScene& scene : allStickingScenes()) {
    INFO(scene.name);
    HingeReference reference(scene);
    std::vector<double> initial;
    for (int i = 0; i <= 200; ++i) {
      reference.advanceTo(scene.window * i / 200.0);
      StickingScene now = scene;
      reference.applyTo(now.world);
      const StickingSolution f = solveStickingForces(now.world, now.points, static_cast<int>(now.contacts.size()));
      for (std::size_t k = 0; k < scene.pivots.size(); ++k) {
        const ContactLoad load = contactLoad(now, f, scene.pivots[k]);
        if (i == 0) initial.push_back(load.normal);
        CHECK(load.normal > 0.25 * initial[k]);
        CHECK(load.requiredMu < 1.1);
      }
    }
  }
}

TEST_CASE("Forward Euler separates the contacts at first order in dt, and semi-implicit Euler too",
          "[exterior_rotation][thesis_claim]") {
  const std::vector<double> dts = halvings(1.0 / 120.0);
  for (const StickingScene& scene : allStickingScenes()) {
    INFO(scene.name);
    for (const StickingMethod m : {StickingMethod::ForwardEuler, StickingMethod::SemiImplicitEuler}) {
      INFO(stickingMethodName(m));
      // The leading error term is O(dt); the next one's share halves with each halving, and from
      // dt = 1/120 s on the local slopes are within 0.1 of 1.
      CHECK(convergenceOrder(dts, maxErrors(scene, m, dts)) == Approx(1.0).margin(0.1));
      const StickingSummary s = runSticking(scene, m, 1.0 / 60.0, stepsOf(scene, 1.0 / 60.0)).summary;
      CHECK(s.maxGap > 1e-4);             // the material points come apart by a tenth of a mm or more
      CHECK(s.minGap > -1e-12);           // and never move into each other (rounding aside)
      CHECK(s.maxPenetration < 1e-12);
    }
  }
}

TEST_CASE("Runge-Kutta with forces held over the step is still first order", "[exterior_rotation][thesis_claim]") {
  const std::vector<double> dts = halvings(1.0 / 120.0);
  for (const StickingScene& scene : allStickingScenes()) {
    INFO(scene.name);
    CHECK(convergenceOrder(dts, maxErrors(scene, StickingMethod::RungeKutta4ConstantForces, dts)) ==
          Approx(1.0).margin(0.1));
  }
}

TEST_CASE("Runge-Kutta with forces re-solved at every stage converges at fourth order",
          "[exterior_rotation][thesis_claim]") {
  const std::vector<double> dts = halvings(1.0 / 60.0);
  for (const StickingScene& scene : allStickingScenes()) {
    INFO(scene.name);
    const std::vector<double> errors = maxErrors(scene, StickingMethod::RungeKutta4ResolvedForces, dts);
    // Measured 4.01-4.03; the finest error (~1e-12 m) is still 1e3 above rounding.
    CHECK(convergenceOrder(dts, errors) == Approx(4.0).margin(0.15));
    CHECK(errors.front() < 1e-6);  // under a micrometre at the thesis' 1/60 s
  }
}

TEST_CASE("The screw update keeps a single hinge on its circle to rounding, but not a double hinge",
          "[exterior_rotation][fix]") {
  for (const StickingScene& scene : {pivotingGroup(), pivotingBox()}) {
    INFO(scene.name);
    const StickingSummary s = runSticking(scene, StickingMethod::ScrewEuler, 1.0 / 30.0, stepsOf(scene, 1.0 / 30.0)).summary;
    CHECK(s.maxError < 1e-13);  // positions of order 0.3 m: a few hundred ulp
    CHECK(s.maxAbsRadialError < 1e-13);
  }
  const StickingScene two = twoFrames();
  const std::vector<double> dts = halvings(1.0 / 60.0);
  CHECK(convergenceOrder(dts, maxErrors(two, StickingMethod::ScrewEuler, dts)) == Approx(1.0).margin(0.1));
  const StickingSummary s = runSticking(two, StickingMethod::ScrewEuler, 1.0 / 60.0, stepsOf(two, 1.0 / 60.0)).summary;
  CHECK(s.minGap < -1e-3);  // B sinks into A by a millimetre or more
}

TEST_CASE("Screw Euler with projection keeps every contact within the projection tolerance",
          "[exterior_rotation][fix]") {
  const ProjectionParams params;
  for (const StickingScene& scene : allStickingScenes()) {
    INFO(scene.name);
    for (const double dt : {1.0 / 30.0, 1.0 / 60.0, 1.0 / 240.0}) {
      const StickingSummary s =
          runSticking(scene, StickingMethod::ScrewEulerProjected, dt, stepsOf(scene, dt)).summary;
      CHECK(s.maxError <= params.positionTolerance);
      // The separating-axis depth of an edge on a face is the edge points' normal gap, plus the
      // test's rounding at the 0.5 m scale of the scene.
      CHECK(s.maxPenetration <= params.positionTolerance + 1e-12);
    }
  }
}

TEST_CASE("The projection returns a displaced box onto its hinge and removes the violating velocity",
          "[exterior_rotation][fix]") {
  StickingScene scene = pivotingBox();
  RigidBody& box = scene.world.bodies[scene.topBody];
  box.s.x += Vec3(0.003, -0.002, 0.001);
  box.updateDerived();
  box.setVelocity(Vec3(0.5, 0.5, 0.0));
  const ProjectionReport report = projectOntoConstraints(scene);
  CHECK(report.errorBefore > 3e-3);
  CHECK(report.errorAfter <= ProjectionParams{}.positionTolerance);
  CHECK(report.iterations <= 3);
  for (std::size_t i = 0; i < scene.points.size(); ++i) {
    const PointConstraint& p = scene.points[i];
    CHECK(box.pointVelocity(box.s.x + box.R * p.rB).norm() < 1e-12);
  }
}

TEST_CASE("The gap is positive for separated points and negative, with an overlap, for interpenetrating ones",
          "[exterior_rotation][invariant]") {
  for (const double shift : {-1e-3, 1e-3}) {
    StickingScene scene = pivotingBox();
    RigidBody& box = scene.world.bodies[scene.topBody];
    box.s.x += shift * (box.R * Vec3::UnitY());  // along the pivot's normal, the box's own y axis
    box.updateDerived();
    for (int i = 0; i < static_cast<int>(scene.points.size()); ++i) CHECK(pointGap(scene, i) == Approx(shift).margin(1e-12));
    if (shift < 0.0) {
      CHECK(deepestPenetration(scene.world) > 0.5 * std::abs(shift));
    } else {
      CHECK(deepestPenetration(scene.world) == 0.0);
    }
  }
}

TEST_CASE("Every sticking method is deterministic", "[exterior_rotation][determinism]") {
  const StickingScene scene = twoFrames();
  for (const StickingMethod m : allStickingMethods()) {
    INFO(stickingMethodName(m));
    const StickingRun a = runSticking(scene, m, 1.0 / 60.0, 12);
    const StickingRun b = runSticking(scene, m, 1.0 / 60.0, 12);
    CHECK(a.end.world.saveState() == b.end.world.saveState());
    CHECK(a.summary.maxError == b.summary.maxError);
  }
}

TEST_CASE("In the thesis' own model, frictionless unilateral LCP forces held by forward Euler, Fig. 6.2's "
          "box separates from the table's edge and Fig. 6.3's table edge sinks into A, both at first order",
          "[exterior_rotation][thesis_claim][unilateral]") {
  // No friction: the box tips and slides over the edge, B slides on A. The LCP's forces act
  // only while the bodies touch; nothing here handles collisions, so each measure is what
  // integrating the forces of the instant does to a contact, the claim of §6.2.
  const StickingScene box = pivotingBox();
  const StickingScene frames = twoFrames();
  const auto extremes = [](const StickingScene& scene, double dt) {
    const UnilateralRun run = runUnilateral(scene, dt, stepsOf(scene, dt));
    std::vector<double> overlap(scene.pivots.size(), 0.0), gap(scene.pivots.size(), 0.0);
    for (const UnilateralSample& s : run.samples)
      for (std::size_t h = 0; h < s.hingeDepth.size(); ++h) {
        overlap[h] = std::max(overlap[h], s.hingeDepth[h]);
        gap[h] = std::max(gap[h], -s.hingeDepth[h]);
      }
    return std::tuple(overlap, gap, run.maxPenetration);
  };
  const auto [boxOverlap, boxGap, boxPenetration] = extremes(box, 1.0 / 60.0);
  const auto [framesOverlap, framesGap, framesPenetration] = extremes(frames, 1.0 / 60.0);
  INFO("Fig. 6.2 at 1/60 s: pivot gap " << boxGap[0] << " m, overlap " << boxPenetration
                                         << " m; Fig. 6.3: pivot overlap " << framesOverlap[0] << " m, hinge gap "
                                         << framesGap[1] << " m, hinge overlap " << framesOverlap[1] << " m");
  // Fig. 6.2: the box lifts off the edge by millimetres (1.9 measured), as under sticking
  // forces; what overlap there is is three orders smaller (1.6 um measured).
  CHECK(boxGap[0] > 1e-3);
  CHECK(boxPenetration < 1e-3 * boxGap[0]);
  // Fig. 6.3: the table's edge sinks into A by more than a millimetre (1.4 measured): the
  // interpenetration the thesis expects; B lifts off A's edge (2.1 mm), overlapping it by no
  // more than micrometres.
  CHECK(framesOverlap[0] > 1e-3);
  CHECK(framesGap[1] > 1e-3);
  CHECK(framesOverlap[1] < 1e-5);
  // Both are errors of the integration: first order in dt.
  const std::vector<double> dts = halvings(1.0 / 120.0);
  std::vector<double> lift, sink;
  for (const double dt : dts) {
    lift.push_back(std::get<1>(extremes(box, dt))[0]);
    sink.push_back(std::get<0>(extremes(frames, dt))[0]);
  }
  INFO("slopes: Fig. 6.2 lift " << convergenceOrder(dts, lift) << ", Fig. 6.3 sink " << convergenceOrder(dts, sink));
  CHECK(convergenceOrder(dts, lift) == Approx(1.0).margin(0.15));
  CHECK(convergenceOrder(dts, sink) == Approx(1.0).margin(0.15));
  CHECK_THROWS_AS(runUnilateral(box, 1.0 / 60.0, 0), std::invalid_argument);
  CHECK_THROWS_AS(runUnilateral(box, -1.0, 10), std::invalid_argument);
}

TEST_CASE("Bad input to the sticking methods is refused with a clear message", "[exterior_rotation][input]") {
  CHECK_THROWS_AS(parseStickingMethod("runge_kutta"), std::invalid_argument);
  for (const StickingMethod m : allStickingMethods()) CHECK(parseStickingMethod(stickingMethodName(m)) == m);
  StickingScene scene = pivotingBox();
  CHECK_THROWS_AS(stepSticking(scene, StickingMethod::ForwardEuler, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(stepSticking(scene, StickingMethod::ForwardEuler, std::nan("")), std::invalid_argument);
  CHECK_THROWS_AS(runSticking(scene, StickingMethod::ForwardEuler, 1.0 / 60.0, 0), std::invalid_argument);
  ProjectionParams bad;
  bad.positionTolerance = 0.0;
  CHECK_THROWS_AS(projectOntoConstraints(scene, bad), std::invalid_argument);
  std::vector<PointConstraint> points = scene.points;
  points[0].a = scene.topBody;
  points[0].b = 1;  // the table: immovable
  CHECK_THROWS_AS(solveStickingForces(scene.world, points, 1), std::invalid_argument);
  points = scene.points;
  points[0].contact = 5;
  CHECK_THROWS_AS(solveStickingForces(scene.world, points, 1), std::invalid_argument);
  StickingScene moving = pivotingBox();
  moving.world.bodies[moving.topBody].setVelocity(Vec3(0.1, 0.0, 0.0));
  CHECK_THROWS_AS(HingeReference(moving), std::invalid_argument);
  HingeReference reference(scene);
  reference.advanceTo(0.1);
  CHECK_THROWS_AS(reference.advanceTo(0.05), std::invalid_argument);
}
