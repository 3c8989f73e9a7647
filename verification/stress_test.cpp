// Randomized stress: every technique of `boxsim run --method` on random scenes
// (random_scenes.hpp: sizes 0.05-5 m, masses up to 1000:1, speeds up to 50 m/s with spins,
// piles, boxes at rest, Δt from 1e-4 s to 1/10 s), every step checked for finite states,
// bodies sinking through the ground and (damped integration) energy rising beyond what the
// scheme's derived sources can add; runStressChecks states each tolerance. The long run of the
// same checks over thousands of seeds is bench/stress_bench.cpp. Then regression tests for what
// the long run found.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <string>

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/impulse_damped/damped_integration.hpp"
#include "boxsim/io/scene_builders.hpp"
#include "boxsim/techniques.hpp"
#include "boxsim/timewarp/timewarp.hpp"
#include "random_scenes.hpp"
#include "test_worlds.hpp"
#include "workload.hpp"

using namespace boxsim;
using namespace boxsim::testing;

namespace {

/// Runs `method` on the scenes of seeds 1..scaledCount(full) (workload.hpp: all `full` of them
/// unless BOXSIM_TEST_WORKLOAD asks for a share) and requires every check to hold on each. When
/// the share is below one scene, the one scene left runs that share of its steps.
void stressSeeds(const std::string& method, long full) {
  RandomSceneSpec spec = affordableSpec(method);
  const auto count = static_cast<unsigned long>(scaledCount(full));
  const double share = static_cast<double>(full) * testWorkload();
  if (share < 1.0)
    spec.steps = std::max(1, static_cast<int>(std::lround(spec.steps * share)));
  long steps = 0;
  for (unsigned long seed = 1; seed <= count; ++seed) {
    const RandomScene scene = randomScene(seed, spec);
    const std::unique_ptr<Stepper> stepper = makeStepper(method);
    const StressOutcome outcome = runStressChecks(scene, *stepper);
    INFO(method << ", " << scene.describe());
    REQUIRE(outcome.failure == "");
    REQUIRE(outcome.steps == scene.steps);
    steps += outcome.steps;
  }
  INFO(method << ": " << count << " scenes, " << steps << " steps");
  CHECK(steps > 0);
}

}  // namespace

TEST_CASE("Random scenes are a pure function of their seed", "[stress][determinism]") {
  for (unsigned long seed : {1ul, 2ul, 77ul}) {
    const RandomScene a = randomScene(seed), b = randomScene(seed);
    REQUIRE(a.world.bodies.size() == b.world.bodies.size());
    CHECK(a.dt == b.dt);
    for (std::size_t i = 0; i < a.world.bodies.size(); ++i) {
      CHECK(a.world.bodies[i].s == b.world.bodies[i].s);
      CHECK(a.world.bodies[i].halfExtents == b.world.bodies[i].halfExtents);
      CHECK(a.world.bodies[i].mass == b.world.bodies[i].mass);
    }
  }
}

TEST_CASE("Random scenes start with no two boxes overlapping and none under the ground",
          "[stress][invariant]") {
  for (unsigned long seed = 1; seed <= 300; ++seed) {
    const RandomScene scene = randomScene(seed);
    const World& w = scene.world;
    for (std::size_t i = 0; i < w.bodies.size(); ++i) {
      if (w.bodies[i].immovable) continue;
      double lowest = w.bodies[i].s.x.y();
      for (int a = 0; a < 3; ++a) lowest -= w.bodies[i].halfExtents[a] * std::abs(w.bodies[i].R(1, a));
      INFO(scene.describe() << ", body " << i);
      CHECK(lowest >= -1e-12);
    }
    // Touching (piles, rows) is allowed; overlap beyond rounding is not.
    for (const ContactManifold& m : findContacts(w, 0.0)) {
      INFO(scene.describe() << ", bodies " << m.a << " and " << m.b);
      CHECK(m.depth <= 1e-9);
    }
  }
}

TEST_CASE("BOXSIM_TEST_WORKLOAD scales the stress seeds and rejects a share not above 0 or "
          "above 1",
          "[stress][workload]") {
  const char* before = std::getenv("BOXSIM_TEST_WORKLOAD");
  const bool wasSet = before != nullptr;
  const std::string saved = wasSet ? before : "";
  ::setenv("BOXSIM_TEST_WORKLOAD", "0.1", 1);
  CHECK(scaledCount(100) == 10);
  CHECK(scaledCount(3) == 1);  // 0.3 rounds to 0, and a scaled test always runs
  for (const char* bad : {"0", "1.5", "-0.1", "", "tenth", "0.1x", "nan"}) {
    ::setenv("BOXSIM_TEST_WORKLOAD", bad, 1);
    INFO("BOXSIM_TEST_WORKLOAD=" << bad);
    CHECK_THROWS_WITH(testWorkload(), Catch::Contains("expected a number in (0, 1]"));
  }
  ::unsetenv("BOXSIM_TEST_WORKLOAD");
  CHECK(scaledCount(100) == 100);
  if (wasSet) ::setenv("BOXSIM_TEST_WORKLOAD", saved.c_str(), 1);
}

// Scene counts: each test case a second or two in a Release build (about 4000 steps in all for
// the impulse-based techniques, a few hundred for the chronological ones, whose resting piles
// meet their event limits every step). BOXSIM_TEST_WORKLOAD (workload.hpp) runs a share of the
// seeds: the sanitize preset runs a tenth.
TEST_CASE("Stress: basic colliding keeps states finite and bodies above the ground",
          "[basic_colliding][stress]") {
  stressSeeds("basic_colliding", 40);
}

TEST_CASE("Stress: the analytic method keeps states finite and bodies above the ground",
          "[analytic_lcp][stress]") {
  stressSeeds("analytic", 60);
}

TEST_CASE("Stress: the plain impulse step keeps states finite and bodies above the ground",
          "[impulse_damped][stress]") {
  stressSeeds("impulse", 100);
}

TEST_CASE("Stress: damped integration keeps states finite, bodies above the ground and energy "
          "within its derived sources",
          "[impulse_damped][stress]") {
  stressSeeds("damped", 100);
}

TEST_CASE("Stress: the simple and safer timewarps keep states finite and bodies above the ground",
          "[timewarp][stress]") {
  stressSeeds("timewarp_simple", 10);
  stressSeeds("timewarp_safer", 10);
}

TEST_CASE("Stress: the swept timewarp keeps states finite and bodies above the ground",
          "[timewarp][stress]") {
  stressSeeds("timewarp_swept", 3);
}

// Regression (random stress, timewarp_simple and timewarp_safer): past its event limit the
// timewarp made every test state valid, also those of bodies whose collisions it had dropped,
// so a resting pile (every contact a collision again each frame) sank through the ground.
TEST_CASE("A timewarp frame that hits its event limit leaves no body sinking into the ground",
          "[timewarp][stress][regression]") {
  for (const TimewarpVariant variant : {TimewarpVariant::Simple, TimewarpVariant::Safer}) {
    World world = groundWorld();
    // A heavy box on two light ones: the collisions between them crowd together (§4.3).
    addBox(world, "bottom", Vec3(0.5, 0.5, 0.5), Vec3(0.0, 0.5, 0.0));
    addBox(world, "middle", Vec3(0.5, 0.5, 0.5), Vec3(0.0, 1.5, 0.0));
    addBox(world, "top", Vec3(0.5, 0.5, 0.5), Vec3(0.0, 2.5, 0.0));
    world.bodies[3].mass = 400.0;
    world.bodies[3].invMass = 1.0 / 400.0;
    world.bodies[3].IbodyInvDiag = 1.0 / 400.0 * world.bodies[1].IbodyInvDiag;
    world.bodies[3].updateDerived();
    TimewarpParams params;
    params.variant = variant;
    params.maxEventsPerStep = 20;
    TimewarpStepper stepper(params);
    bool limited = false;
    const double dt = 1.0 / 60.0;
    for (int k = 0; k < 60; ++k) limited = stepper.step(world, dt).limitReached || limited;
    REQUIRE(limited);
    // Lowest face of each box: never deeper into what it rests on than the slop of
    // FIXINTERPENETRATION plus one step of gravity's travel.
    const double tolerance = FixContactParams{}.slop * 0.5 + 9.81 * dt * dt;
    INFO(timewarpMethodName(variant));
    CHECK(world.bodies[1].s.x.y() - 0.5 >= -tolerance);
    CHECK(world.bodies[2].s.x.y() - world.bodies[1].s.x.y() >= 1.0 - tolerance);
    CHECK(world.bodies[3].s.x.y() - world.bodies[2].s.x.y() >= 1.0 - tolerance);
  }
}

// Regression (stress seed 103): a slow body near a moved fast one stands at its predicted pose
// for their narrow phase, so the box on the fast plate is found in both gathering modes and
// stops in the first step. The story: chapters/impulse_damped/README.md, "Gathering contacts
// once per step".
TEST_CASE("Once-per-step gathering finds the contact of a slow box resting on a fast plate",
          "[impulse_damped][stress][regression]") {
  for (const ContactGatheringMode mode :
       {ContactGatheringMode::EveryPass, ContactGatheringMode::OncePerStep}) {
    RandomScene scene = randomScene(103, affordableSpec("damped"));
    REQUIRE(scene.world.bodies.size() == 4);
    DampedIntegrationParams params;
    params.impulse.gathering = mode;
    DampedIntegrationStepper stepper(params);
    stepper.step(scene.world, scene.dt);
    INFO(contactGatheringName(mode));
    CHECK(scene.world.bodies[3].v.y() == 0.0);
  }
}

// Regression (stress seed 22811): COLLIDE acts after the revert with the state's inertia, so
// each impulse changes the energy by ½ j (1 - e) v⁻ <= 0 and the spinning plate's step stays
// within the derived energy sources. The story: chapters/impulse_damped/README.md, "The
// constants of A.2".
TEST_CASE("A fast-spinning thin plate striking the ground does not leave with more energy",
          "[impulse_damped][stress][regression]") {
  for (const ContactGatheringMode mode :
       {ContactGatheringMode::EveryPass, ContactGatheringMode::OncePerStep}) {
    const RandomScene scene = randomScene(22811, affordableSpec("damped"));
    DampedIntegrationParams params;
    params.impulse.gathering = mode;
    DampedIntegrationStepper stepper(params);
    REQUIRE(stepper.name() == "damped");
    const StressOutcome outcome = runStressChecks(scene, stepper);
    INFO(contactGatheringName(mode) << ", " << scene.describe() << ", largest energy rise "
                                    << outcome.largestEnergyRise << " J");
    CHECK(outcome.failure == "");
    CHECK(outcome.steps == scene.steps);
  }
}

// Regression (stress seeds 11943, 16376, 24094, Δt = 0.1 s): FIXCONTACTCONSTRAINTS may lift a
// body as far as the step can have carried it (fixLiftLimit), so none sinks on. The story:
// chapters/impulse_damped/README.md, "The constants of A.2".
TEST_CASE("At a large step a body driven into the ground is lifted back out",
          "[impulse_damped][stress][regression]") {
  for (const unsigned long seed : {11943ul, 16376ul, 24094ul}) {
    const RandomScene scene = randomScene(seed, affordableSpec("damped"));
    REQUIRE(scene.dt == Approx(0.1));
    DampedIntegrationStepper stepper;
    const StressOutcome outcome = runStressChecks(scene, stepper);
    INFO(scene.describe() << ", deepest under the ground " << outcome.deepestBelowGround << " m");
    CHECK(outcome.failure == "");
    CHECK(outcome.steps == scene.steps);
  }
}
