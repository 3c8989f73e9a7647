// Verification of the basic colliding technique (thesis §2.1, §3.3.1, §4.3): collisions
// against closed-form answers, the bisection bracket, the third-body restart, the bounded
// chattering, and determinism.
#include <catch2/catch.hpp>
#include <cmath>

#include "boxsim/basic_colliding/basic_colliding.hpp"
#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/io/recorder.hpp"
#include "boxsim/io/scene.hpp"
#include "boxsim/io/simulate.hpp"

using namespace boxsim;

namespace {

World cubeAbove(double bottomHeight, double dropSpeed = 0.0) {
  World world;
  world.addGround(0.0, 10.0);
  RigidBody b = RigidBody::box(Vec3(0.5, 0.5, 0.5), 1.0);
  b.s.x = Vec3(0.0, bottomHeight + 0.5, 0.0);
  b.updateDerived();
  b.setVelocity(Vec3(0.0, -dropSpeed, 0.0));
  world.add(b, "cube");
  return world;
}

/// Highest bottom height reached after the first bounce of a cube dropped flat from h0.
double firstReboundHeight(double h0, double dt, const BasicCollidingParams& params) {
  World world = cubeAbove(h0);
  BasicCollidingStepper stepper(params);
  bool bounced = false;
  double peak = 0.0;
  for (int k = 0; k < static_cast<int>(3.0 / dt); ++k) {
    const StepStats s = stepper.step(world, dt);
    bounced = bounced || s.events > 0;
    const double bottom = world.bodies[1].s.x.y() - 0.5;
    if (bounced && world.bodies[1].v.y() < 0.0 && peak > 0.0) break;  // past the apex
    if (bounced) peak = std::max(peak, bottom);
  }
  return peak;
}

}  // namespace

TEST_CASE("A head-on collision conserves linear momentum and reverses the normal velocity times e",
          "[basic_colliding][closed_form]") {
  World world;
  world.gravity = Vec3::Zero();
  RigidBody a = RigidBody::box(Vec3(0.5, 0.5, 0.5), 1.0);
  RigidBody b = RigidBody::box(Vec3(0.5, 0.5, 0.5), 3.0);
  a.s.x = Vec3(-2.0, 0.0, 0.0);
  b.s.x = Vec3(2.0, 0.0, 0.0);
  a.setVelocity(Vec3(3.0, 0.0, 0.0));
  b.setVelocity(Vec3(-2.0, 0.0, 0.0));  // total momentum -3 kg m/s
  world.add(a, "a");
  world.add(b, "b");
  const Vec3 momentum = world.linearMomentum();
  const double approach = world.bodies[1].v.x() - world.bodies[0].v.x();  // -5 m/s
  BasicCollidingStepper stepper;
  int events = 0;
  for (int k = 0; k < 120; ++k) events += stepper.step(world, 1.0 / 60.0).events;
  CHECK(events == 1);
  // Impulses are equal and opposite; only rounding (~1e-16 relative) may differ.
  REQUIRE(momentum.norm() == Approx(3.0));
  CHECK((world.linearMomentum() - momentum).norm() < 1e-13);
  const double separation = world.bodies[1].v.x() - world.bodies[0].v.x();
  CHECK(separation == Approx(-world.restitution * approach).epsilon(1e-12));
  // A face-face contact on the line of centres applies no torque.
  CHECK(world.bodies[0].omega.norm() < 1e-12);
}

TEST_CASE("A box dropped flat rebounds to e^2 of its drop height within the integrator's error",
          "[basic_colliding][closed_form]") {
  const double h0 = 1.0, g = 9.81, e = 0.9;
  for (Integrator integrator : {Integrator::SemiImplicitEuler, Integrator::ForwardEuler}) {
    BasicCollidingParams params;
    params.integrator = integrator;
    for (double dt : {1.0 / 240.0, 1.0 / 960.0}) {
      const double ratio = firstReboundHeight(h0, dt, params) / h0;
      // Tolerance, derived: in free flight forward Euler gains and semi-implicit Euler loses
      // exactly g² dt² / 2 of specific energy per step (see the free-flight test's closed form),
      // so over the fall and the rise (times T_d and T_u = e T_d) the apex height is off by at
      // most g dt (T_d + T_u) / 2. Sampling the apex only at frames misses at most g dt² / 8,
      // and the impulse is applied up to v tol above the ground.
      const double Td = std::sqrt(2.0 * h0 / g), Tu = e * Td, v = g * Td;
      const double bound = g * dt * (Td + Tu) / (2.0 * h0) + g * dt * dt / (8.0 * h0) +
                           v * params.timeOfImpact.timeTolerance / h0;
      INFO(integratorName(integrator) << ", dt = " << dt << ", rebound ratio = " << ratio
                                      << ", e^2 = " << e * e << ", bound = " << bound);
      CHECK(std::abs(ratio - e * e) <= bound);
    }
  }
}

TEST_CASE("Bisection brackets the contact time within its tolerance", "[basic_colliding][closed_form]") {
  // With no gravity the fall is linear and Euler is exact: contact at t* = gap / v.
  World world = cubeAbove(0.0123, 2.0);
  world.gravity = Vec3::Zero();
  const WorldState start = world.saveState();
  const double span = 1.0 / 60.0, tStar = 0.0123 / 2.0;
  integrateWorld(world, span, Integrator::ForwardEuler);
  const std::pair<int, int> first = firstIntersectingPair(world, 0.0);
  REQUIRE(first == std::make_pair(0, 1));
  TimeOfImpactParams params;
  const TimeOfImpact toi = findTimeOfImpact(world, start, span, first, Integrator::ForwardEuler, params);
  CHECK(toi.tSeparated <= tStar);
  CHECK(toi.tIntersecting >= tStar);
  CHECK(toi.tIntersecting - toi.tSeparated <= params.timeTolerance);
  CHECK(toi.bisections == static_cast<int>(std::ceil(std::log2(span / params.timeTolerance))));
  // The world is left rolled back to the separated end of the bracket.
  CHECK(world.bodies[1].s.x.y() - 0.5 == Approx(0.0123 - 2.0 * toi.tSeparated).margin(1e-15));
}

TEST_CASE("The search restarts on an earlier collision with a third body (§3.3.1)",
          "[basic_colliding][claim]") {
  // Two cubes fall onto the ground at constant speed; the later-listed one lands first, but the
  // pair found first at the end of the step is the earlier-listed one.
  World world;
  world.gravity = Vec3::Zero();
  world.addGround(0.0, 10.0);
  RigidBody slow = RigidBody::box(Vec3(0.5, 0.5, 0.5), 1.0);
  slow.s.x = Vec3(-3.0, 0.5 + 0.010, 0.0);
  slow.setVelocity(Vec3(0.0, -1.0, 0.0));  // lands at t = 0.010 s
  RigidBody fast = slow;
  fast.s.x = Vec3(3.0, 0.5 + 0.004, 0.0);
  fast.setVelocity(Vec3(0.0, -1.0, 0.0));  // lands at t = 0.004 s
  world.add(slow, "slow");
  world.add(fast, "fast");
  const WorldState start = world.saveState();
  integrateWorld(world, 0.016, Integrator::ForwardEuler);
  const std::pair<int, int> first = firstIntersectingPair(world, 0.0);
  REQUIRE(first == std::make_pair(0, 1));
  const TimeOfImpact toi = findTimeOfImpact(world, start, 0.016, first, Integrator::ForwardEuler);
  CHECK(toi.restarts >= 1);
  CHECK(toi.pair == std::make_pair(0, 2));
  CHECK(toi.tSeparated <= 0.004);
  CHECK(toi.tIntersecting >= 0.004);
}

TEST_CASE("Chattering to rest is bounded by the events-per-step limit instead of hanging (§4.3)",
          "[basic_colliding][chatter]") {
  World world = cubeAbove(0.5);
  BasicCollidingStepper stepper;
  const double dt = 1.0 / 60.0;
  long limited = 0, eventsFirstSecond = 0, eventsLastSecond = 0;
  double lowestBottom = 1.0;
  const int steps = 8 * 60;
  for (int k = 0; k < steps; ++k) {
    const StepStats s = stepper.step(world, dt);
    limited += s.limitReached ? 1 : 0;
    if (k < 60) eventsFirstSecond += s.events;
    if (k >= steps - 60) eventsLastSecond += s.events;
    lowestBottom = std::min(lowestBottom, world.bodies[1].s.x.y() - 0.5);
  }
  INFO("events in the first second " << eventsFirstSecond << ", in the last " << eventsLastSecond);
  // Bounce intervals shrink by e per bounce (Zeno): the collisions crowd together...
  CHECK(eventsLastSecond > 20 * eventsFirstSecond);
  // ...until steps hit the limit, and every committed state is still collision free (within the
  // technique's intersection threshold).
  CHECK(limited > 0);
  CHECK(lowestBottom >= -stepper.params().timeOfImpact.depthTolerance);
}

TEST_CASE("The same scene twice gives a bit-identical trajectory", "[basic_colliding][determinism]") {
  const std::string path = std::string(BOXSIM_SOURCE_DIR) + "/chapters/basic_colliding/scenes/die.json";
  std::string text[2];
  for (std::string& t : text) {
    Scene scene = loadScene(path);
    BasicCollidingStepper stepper;
    Recorder recorder(scene.world, {{"seed", "0"}});
    SimulateOptions options;
    options.duration = 3.0;
    simulate(scene.world, stepper, options, recorder);
    t = formatTrajectory(recorder.trajectory());
  }
  CHECK(text[0].size() > 1000);
  CHECK(text[0] == text[1]);
}

TEST_CASE("A box that chatters at rest does not stop a falling box elsewhere",
          "[basic_colliding][chatter]") {
  // A cube resting on the ground from t = 0 collides again the instant gravity pulls it in, so
  // every step hits the events limit; only that cube may be held, not the whole world.
  World world;
  world.addGround(0.0, 20.0);
  RigidBody resting = RigidBody::box(Vec3(0.5, 0.5, 0.5), 1.0);
  resting.s.x = Vec3(-5.0, 0.5, 0.0);
  resting.updateDerived();
  RigidBody falling = resting;
  falling.s.x = Vec3(5.0, 10.0, 0.0);
  falling.updateDerived();
  world.add(resting, "resting");
  world.add(falling, "falling");
  BasicCollidingStepper stepper;
  const double dt = 1.0 / 60.0;
  bool limited = false;
  for (int k = 0; k < 30; ++k) limited = stepper.step(world, dt).limitReached || limited;
  CHECK(limited);
  // Half a second of free fall, integrated in pieces as the resting cube's collisions split the
  // steps: semi-implicit Euler falls further than the exact g t² / 2 by at most g t dt / 2 per
  // piece size, so by at most g t dt / 2 overall.
  const double t = 0.5, exact = 10.0 - 0.5 * 9.81 * t * t;
  const double y = world.bodies[2].s.x.y();
  CHECK(y <= exact);
  CHECK(y >= exact - 0.5 * 9.81 * t * dt - 1e-12);
  CHECK(world.bodies[1].s.x.y() >= 0.5 - 1e-9);
}

TEST_CASE("Bad basic colliding parameters are refused", "[basic_colliding][input]") {
  BasicCollidingParams zeroTolerance;
  zeroTolerance.timeOfImpact.timeTolerance = 0.0;
  CHECK_THROWS_AS(BasicCollidingStepper(zeroTolerance), std::invalid_argument);
  BasicCollidingParams noEvents;
  noEvents.maxEventsPerStep = 0;
  CHECK_THROWS_AS(BasicCollidingStepper(noEvents), std::invalid_argument);
}
