// Determinism (DESIGN.md): the same scene and parameters give a bit-identical trajectory. Every
// technique runs the same many-contact scene twice in one process, and every double of every
// body's state (x, q, P, L) is compared bit for bit after every step; then once with each broad
// phase (World::broadPhase), which must find the same pairs in the same order and so leave the
// trajectory unchanged to the last bit. Across builds (Release against Debug),
// cmake/compare_builds.sh compares the trajectory files of the shipped scenes.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstring>
#include <memory>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/impulse_damped/contact_islands.hpp"
#include "boxsim/impulse_damped/damped_integration.hpp"
#include "boxsim/impulse_damped/impulse_stepper.hpp"
#include "boxsim/io/scene_builders.hpp"
#include "boxsim/techniques.hpp"
#include "boxsim/timewarp/timewarp.hpp"
#include "test_worlds.hpp"
#include "workload.hpp"

using namespace boxsim;

namespace {

/// A pyramid of base 3 (6 unit cubes, every one touching its neighbours and the ground) and a
/// die dropped spinning onto its apex: resting contacts, a collision and sliding in one scene.
World manyContacts() {
  World world = testing::groundWorld();
  PyramidSpec pyramid;
  pyramid.base = 3;
  addPyramid(world, pyramid);
  DieSpec die;
  die.position = Vec3(0.2, 6.0, 0.1);
  die.angularVelocity = Vec3(1.0, 2.0, -0.5);
  addDie(world, die);
  return world;
}

/// A clump of 5 × 5 × 5 unit cubes 0.2 m apart, its lowest layer 1.7 m above the ground, each
/// cube moving at 20 m/s downwards besides the clump's own 5 m/s towards its centre. The cubes
/// move a third of a metre a step, far beyond the gathering's exact reach, so the once-per-step
/// contact gathering stretches their bounds along their way (its explicit-bounds broad phase)
/// and moves them to their predicted poses pass by pass; they collide among themselves from the
/// third step and the bottom layer strikes the ground in the sixth. 125 bodies: past the 64 from
/// which sweep and prune may pair them through its uniform grid instead of the sweep.
World fastClump() {
  World world = testing::groundWorld();
  ClumpSpec clump;
  clump.count = 125;
  clump.spacing = 1.2;
  clump.center = Vec3(0.0, 4.6, 0.0);
  addClump(world, clump);
  for (RigidBody& body : world.bodies)
    if (!body.immovable) body.setVelocity(body.v + Vec3(0.0, -20.0, 0.0));
  return world;
}

/// The fast clump with Coulomb friction (mu = 0.5) on every body, beside a pyramid of base 3
/// 40 m away that settles apart from it.
World frictionalClump() {
  World world = fastClump();
  PyramidSpec far;
  far.base = 3;
  far.origin = Vec3(40.0, 0.0, 0.0);
  addPyramid(world, far);
  for (RigidBody& body : world.bodies) body.friction = {0.5, 0.5};
  return world;
}

/// makeStepper(method), except that the swept timewarp stops a frame after its share of 1000
/// events (workload.hpp; all 1000, its default, unless BOXSIM_TEST_WORKLOAD asks for less).
std::unique_ptr<Stepper> stepperOf(const std::string& method) {
  if (method != timewarpMethodName(TimewarpVariant::Swept)) return makeStepper(method);
  TimewarpParams params;
  params.variant = TimewarpVariant::Swept;
  params.maxEventsPerStep = static_cast<int>(testing::scaledCount(params.maxEventsPerStep));
  return std::make_unique<TimewarpStepper>(params);
}

/// Appends every double of every body's state (x, q, P, L) to `out`.
void appendStates(const World& world, std::vector<double>& out) {
  for (const RigidBody& b : world.bodies) {
    out.insert(out.end(), b.s.x.data(), b.s.x.data() + 3);
    out.insert(out.end(), b.s.q.coeffs().data(), b.s.q.coeffs().data() + 4);
    out.insert(out.end(), b.s.P.data(), b.s.P.data() + 3);
    out.insert(out.end(), b.s.L.data(), b.s.L.data() + 3);
  }
}

/// Every double of every body's state after each step of `method` on `start` run with the
/// broad phase `kind`, in order.
std::vector<double> trajectory(const std::string& method, int steps,
                               BroadPhase kind = BroadPhase::SweepAndPrune,
                               const World& start = manyContacts()) {
  World world = start;
  world.broadPhase = kind;
  const std::unique_ptr<Stepper> stepper = stepperOf(method);
  std::vector<double> out;
  for (int k = 0; k < steps; ++k) {
    stepper->step(world, 1.0 / 60.0);
    appendStates(world, out);
  }
  return out;
}

/// Steps of `method` on manyContacts(): 1 s; the chronological techniques meet their event
/// limits on the resting pyramid every step, so they run a tenth of it, and the swept timewarp,
/// whose conservative advancement makes each of its 1000 events a frame dear (2.5 s a frame
/// here), one frame. BOXSIM_TEST_WORKLOAD scales the counts (workload.hpp).
int stepsOf(const std::string& method) {
  const bool chronological = method != "impulse" && method != "damped";
  return method == "timewarp_swept" ? 1
                                    : static_cast<int>(testing::scaledCount(chronological ? 6 : 60));
}

/// True when a and b hold the same non-empty sequence of doubles, bit for bit: memcmp, not
/// ==, so -0.0 against 0.0 and NaN against NaN count as different.
bool sameBits(const std::vector<double>& a, const std::vector<double>& b) {
  return !a.empty() && a.size() == b.size() &&
         std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

}  // namespace

TEST_CASE("Every technique gives a bit-identical trajectory when run twice on a scene of many "
          "contacts",
          "[techniques][determinism]") {
  for (const std::string& method : methodNames()) {
    const int steps = stepsOf(method);
    const std::vector<double> first = trajectory(method, steps);
    const std::vector<double> second = trajectory(method, steps);
    INFO(method);
    CHECK(sameBits(first, second));
  }
}

TEST_CASE("Every technique gives the same trajectory, bit for bit, with the broad phase on "
          "(sweep and prune) and off (all pairs)",
          "[techniques][determinism][broad_phase]") {
  for (const std::string& method : methodNames()) {
    const int steps = stepsOf(method);
    const std::vector<double> on = trajectory(method, steps, BroadPhase::SweepAndPrune);
    const std::vector<double> off = trajectory(method, steps, BroadPhase::AllPairs);
    INFO(method);
    CHECK(sameBits(on, off));
  }
}

TEST_CASE("Impulse and damped give the same trajectory, bit for bit, with either broad phase on "
          "a fast clump hitting the ground",
          "[impulse_damped][determinism][broad_phase]") {
  const World start = fastClump();
  for (const std::string& method : {std::string("impulse"), std::string("damped")}) {
    // 0.5 s: the impacts of the first 0.1 s, then the clump rebounding (restitution 0.9) with
    // cubes still striking the ground and each other; at least the 6 steps to the ground under
    // a smaller BOXSIM_TEST_WORKLOAD.
    const int steps = static_cast<int>(std::max(6L, testing::scaledCount(30)));
    const std::vector<double> on = trajectory(method, steps, BroadPhase::SweepAndPrune, start);
    const std::vector<double> off = trajectory(method, steps, BroadPhase::AllPairs, start);
    INFO(method);
    CHECK(sameBits(on, off));
  }
}

TEST_CASE("Damped integration gives the same bits whether or not it stops the collision passes "
          "after one that changed nothing, and does stop them",
          "[impulse_damped][determinism]") {
  for (const World& start : {manyContacts(), fastClump()}) {
    std::vector<double> states[2];
    int passes[2] = {0, 0};
    for (int stop = 0; stop < 2; ++stop) {
      DampedIntegrationParams params;
      params.stopUnchangedCollisionPasses = stop == 1;
      params.islandSettling = false;  // the stop alone
      DampedIntegrationStepper stepper(params);
      World world = start;
      for (int k = 0; k < static_cast<int>(std::max(6L, testing::scaledCount(60))); ++k) {
        passes[stop] += stepper.step(world, 1.0 / 60.0).passes;
        appendStates(world, states[stop]);
      }
    }
    CHECK(sameBits(states[0], states[1]));
    // The resting pyramid and the clump once it rests leave collision passes with nothing to do.
    CHECK(passes[1] < passes[0]);
  }
}

/// Fig. 6.7's clump read 20 m up (clump100.json: 100 unit cubes on a 2 m grid, each at 5 m/s
/// towards the centre) with Coulomb friction (mu = 0.5) and restitution 0.5. Its cubes meet in
/// mid-air in islands that settle. A friction impulse below the rounding of the momenta still
/// adds to its pair's sums, and an island counted as settled by its momenta alone skipped the
/// passes that would have added more: the bits parted from A.2's as written at step 82. Run with
/// the passes alone (DampedIntegrationParams::shockPropagation off), where it showed.
World frictionalMidAirClump() {
  World world;
  world.addGround(0.0, 150.0);
  world.restitution = 0.5;
  ClumpSpec clump;
  clump.count = 100;
  clump.spacing = 2.0;
  clump.center = Vec3(0.0, 20.0, 0.0);
  clump.speed = 5.0;
  addClump(world, clump);
  for (RigidBody& body : world.bodies) body.friction = {0.5, 0.5};
  return world;
}

/// A unit cube on the ground sliding at 30 m/s towards a heavy block (1000 kg) 0.45 m away,
/// with two cubes resting side by side 0.2 m behind it. The step's candidate pairs join the
/// slider to the block only: the two resting cubes are an island of their own, which the first
/// collision pass leaves unchanged. That pass bounces the slider back at 27 m/s; the next
/// finds it in the first resting cube, whose push into the second must follow in the same pass:
/// the pairs grown for the slider join the settled island to its own again.
World ricochet() {
  World world = testing::groundWorld();
  world.restitution = 0.9;
  const Vec3 h(0.5, 0.5, 0.5);
  const auto place = [&](RigidBody body, double x, const std::string& name) {
    body.s.x = Vec3(x, 0.5, 0.0);
    body.updateDerived();
    return world.add(body, name);
  };
  place(RigidBody::box(h, 1000.0), -1.45, "block");
  const int slider = place(RigidBody::box(h, 1.0), 0.0, "slider");
  place(RigidBody::box(h, 1.0), 1.2, "first");
  place(RigidBody::box(h, 1.0), 2.2, "second");
  world.bodies[static_cast<std::size_t>(slider)].setVelocity(Vec3(-30.0, 0.0, 0.0));
  return world;
}

TEST_CASE("Damped integration gives the same bits whether or not settled islands sit out the "
          "rest of their passes, and islands do sit passes out",
          "[impulse_damped][determinism][islands]") {
  // Five scenes: a resting pyramid hit by a die; the fast clump, whose cubes fly apart after
  // their impacts; the same clump with Coulomb friction (mu = 0.5) beside a far pyramid,
  // which settles apart from it; the ricochet into a settled island; and Fig. 6.7's clump
  // meeting in mid-air with friction. Sleeping is on (the stepper's default), so sleepers stand
  // in as immovable between islands and wake within passes.
  const World frictional = frictionalClump();
  // At least half a second even under a reduced workload: the fast clump's cubes need about
  // 18 steps (0.3 s) to fly apart into islands that settle.
  const int steps = static_cast<int>(std::max(30L, testing::scaledCount(90)));
  const World scenes[] = {manyContacts(), fastClump(), frictional, ricochet(),
                          frictionalMidAirClump()};
  for (const World& start : scenes) {
    const bool isRicochet = &start == &scenes[3];
    const bool passesAlone = &start == &scenes[4];
    std::vector<double> states[2];
    long skipped[2] = {0, 0};
    for (int islands = 0; islands < 2; ++islands) {
      // Off: every pass of both loops for every body, A.2 as written (no early stop at all).
      DampedIntegrationParams params;
      params.islandSettling = islands == 1;
      params.stopUnchangedCollisionPasses = islands == 1;
      params.shockPropagation = !passesAlone;
      DampedIntegrationStepper stepper(params);
      World world = start;
      for (int k = 0; k < steps; ++k) {
        stepper.step(world, 1.0 / 60.0);
        appendStates(world, states[islands]);
      }
      skipped[islands] = stepper.gathering().skippedBodyPasses();
    }
    CHECK(sameBits(states[0], states[1]));
    CHECK(skipped[0] == 0);
    if (!isRicochet) {
      CHECK(skipped[1] > 0);
    } else {
      // The second cube is pushed within the first step: its state (13 doubles a body, the
      // ground and three bodies before it) has P_x > 0 after it.
      CHECK(states[1][4 * 13 + 7] > 0.0);
    }
  }
}

TEST_CASE("A sleeper joins its partners' islands: what may wake it and what it may push settle "
          "together", "[impulse_damped][determinism][islands]") {
  // Bodies: 0 the ground, 1 a sleeper standing in as immovable, 2 resting on the sleeper, 3
  // beside it on the ground touching the sleeper, 4-5 resting on the ground apart. The
  // gathering counts the sleeper as movable (it may wake), so it joins 2 and 3 into one island;
  // the ground joins nothing.
  ContactIslands islands;
  islands.reset({0, 1, 1, 1, 1, 1});
  for (const auto& [a, b] : {std::pair{1, 2}, {1, 3}, {0, 3}, {0, 4}, {4, 5}}) islands.join(a, b);
  islands.flatten();
  // A pass in which 2 changed (a contact woke the sleeper under it, say): 1-3 stay active with
  // it, 4-5 settle.
  islands.markChanged(2);
  CHECK_FALSE(islands.settleUnchanged());
  CHECK_FALSE(islands.settled(1));
  CHECK_FALSE(islands.settled(3));
  CHECK(islands.settled(4));
  CHECK(islands.settled(5));
  // A pass that changed none of it: the sleeper's island settles too, the ground never counts.
  CHECK(islands.settleUnchanged());
  CHECK(islands.settled(1));
  CHECK(islands.settled(3));
  CHECK_FALSE(islands.settled(0));
  // Counted as immovable, the sleeper would join nothing: 2 and 3 are islands of their own.
  islands.reset({0, 0, 1, 1, 1, 1});
  for (const auto& [a, b] : {std::pair{1, 2}, {1, 3}, {0, 3}, {0, 4}, {4, 5}}) islands.join(a, b);
  islands.markChanged(2);
  CHECK_FALSE(islands.settleUnchanged());
  CHECK_FALSE(islands.settled(2));
  CHECK(islands.settled(3));
  CHECK_FALSE(islands.settled(1));
}

TEST_CASE("Damped integration gives the same bits whether or not it keeps the narrow phases of "
          "poses that have not changed, and keeping spares tests",
          "[impulse_damped][determinism][kept]") {
  // The resting pyramid hit by a die, the fast clump, and the clump with Coulomb friction on a
  // far pyramid (contacts at rest, impacts, friction's patches).
  const World frictional = frictionalClump();
  const int steps = static_cast<int>(std::max(30L, testing::scaledCount(90)));
  for (const World& start : {manyContacts(), fastClump(), frictional}) {
    std::vector<double> states[2];
    long tests[2] = {0, 0}, reuses[2] = {0, 0}, checks[2] = {0, 0};
    for (int keep = 0; keep < 2; ++keep) {
      DampedIntegrationParams params;
      params.impulse.keepNarrowPhases = keep == 1;
      DampedIntegrationStepper stepper(params);
      World world = start;
      for (int k = 0; k < steps; ++k) {
        stepper.step(world, 1.0 / 60.0);
        appendStates(world, states[keep]);
      }
      tests[keep] = stepper.gathering().kept().tests();
      reuses[keep] = stepper.gathering().kept().reuses();
      checks[keep] = stepper.gathering().kept().axisChecks();
    }
    CHECK(sameBits(states[0], states[1]));
    CHECK(reuses[0] == 0);
    CHECK(checks[0] == 0);
    CHECK(reuses[1] > 0);
    // What is handed back, or settled along the last test's axis, is what would have run.
    CHECK(tests[1] + reuses[1] + checks[1] == tests[0]);
  }
}

TEST_CASE("Worlds stepped on separate threads at the same time give the same bits as one after "
          "another",
          "[techniques][determinism][threads]") {
  // The library's thread rule (docs/library.md): no state is shared between steppers, so each
  // world with its own stepper may run on a thread of its own. Five techniques, the damped one
  // with the visual plausibility's random generator on, run at once on five threads and then
  // one after another on this thread; every body state after every step must agree bit for bit.
  const auto stepperFor = [](const std::string& method) {
    TechniqueOptions options;
    if (method == "damped") options.plausibilitySeed = 7;
    return makeStepper(method, options);
  };
  const std::vector<std::string> methods = {"damped", "impulse", "analytic", "basic_colliding",
                                            "timewarp_safer"};
  const auto run = [&](const std::string& method, std::vector<double>& out) {
    World world = manyContacts();
    const std::unique_ptr<Stepper> stepper = stepperFor(method);
    for (int k = 0; k < stepsOf(method); ++k) {
      stepper->step(world, 1.0 / 60.0);
      appendStates(world, out);
    }
  };
  std::vector<std::vector<double>> together(methods.size()), alone(methods.size());
  {
    std::vector<std::thread> threads;
    for (std::size_t m = 0; m < methods.size(); ++m)
      threads.emplace_back(run, std::cref(methods[m]), std::ref(together[m]));
    for (std::thread& thread : threads) thread.join();
  }
  for (std::size_t m = 0; m < methods.size(); ++m) {
    run(methods[m], alone[m]);
    INFO(methods[m]);
    CHECK(sameBits(together[m], alone[m]));
  }
}

TEST_CASE("Impulse and damped give the same bits on any number of threads: COLLIDE's contacts "
          "run in dependency levels of A.2's own order, the fast pairs' narrow phases each into "
          "its own slot",
          "[impulse_damped][determinism][threads]") {
  // The resting pyramid hit by a die (its cubes fall asleep, and the die wakes them: passes with
  // a sleeper beside an awake body run in order), the fast clump, and the clump with Coulomb
  // friction beside a far pyramid. Every pass with two contacts or more is shared among the
  // threads (parallelContacts 0), so the levels carry nearly every pass, and so is every pass
  // with a narrow phase of a pair with a fast body (parallelNarrowPhases 0).
  const World frictional = frictionalClump();
  const int steps = static_cast<int>(std::max(40L, testing::scaledCount(120)));
  for (const World& start : {manyContacts(), fastClump(), frictional}) {
    std::vector<double> damped[4], impulse[4];
    long levelPasses[4] = {0, 0, 0, 0}, testPasses[4] = {0, 0, 0, 0};
    const int threadCounts[4] = {1, 2, 3, 8};
    for (int t = 0; t < 4; ++t) {
      DampedIntegrationParams params;
      params.impulse.threads = threadCounts[t];
      params.impulse.parallelContacts = 0;
      params.impulse.parallelNarrowPhases = 0;
      DampedIntegrationStepper stepper(params);
      ImpulseStepperParams plainParams;
      plainParams.impulse.threads = threadCounts[t];
      plainParams.impulse.parallelContacts = 0;
      plainParams.impulse.parallelNarrowPhases = 0;
      ImpulseStepper plain(plainParams);
      World world = start, plainWorld = start;
      for (int k = 0; k < steps; ++k) {
        stepper.step(world, 1.0 / 60.0);
        appendStates(world, damped[t]);
        plain.step(plainWorld, 1.0 / 60.0);
        appendStates(plainWorld, impulse[t]);
      }
      levelPasses[t] = stepper.gathering().levelPasses();
      testPasses[t] = stepper.gathering().parallelTestPasses();
    }
    CHECK(levelPasses[0] == 0);  // one thread: the loop in order
    CHECK(testPasses[0] == 0);   // and each pair tested as it is planned
    for (int t = 1; t < 4; ++t) {
      CHECK(sameBits(damped[0], damped[t]));
      CHECK(sameBits(impulse[0], impulse[t]));
      // The same passes in levels for any number of threads above one, and most of them.
      CHECK(levelPasses[t] == levelPasses[1]);
      CHECK(testPasses[t] == testPasses[1]);
    }
    CHECK(levelPasses[1] > 0);
    CHECK(testPasses[1] > 0);
  }
}

TEST_CASE("With the predicted anchor or edge corners damped integration gives the same bits on "
          "any number of threads and run after run",
          "[impulse_damped][determinism][threads]") {
  // ImpulseParams::predictedAnchor: the bodies fast at a step's start are cached where its
  // first pass predicts them; ImpulseParams::edgeCorners: an edge-edge pair keeps its face's
  // corners. The fast clump, whose cubes are such bodies at every step, and the clump with
  // Coulomb friction, each pass shared among the threads as above.
  const int steps = static_cast<int>(std::max(40L, testing::scaledCount(120)));
  for (const bool corners : {false, true}) {
    for (const World& start : {fastClump(), frictionalClump()}) {
      std::vector<double> damped[4];
      const int threadCounts[4] = {1, 1, 2, 3};
      for (int t = 0; t < 4; ++t) {
        DampedIntegrationParams params;
        params.impulse.predictedAnchor = !corners;
        params.impulse.edgeCorners = corners;
        params.impulse.threads = threadCounts[t];
        params.impulse.parallelContacts = 0;
        params.impulse.parallelNarrowPhases = 0;
        DampedIntegrationStepper stepper(params);
        World world = start;
        for (int k = 0; k < steps; ++k) {
          stepper.step(world, 1.0 / 60.0);
          appendStates(world, damped[t]);
        }
      }
      for (int t = 1; t < 4; ++t) CHECK(sameBits(damped[0], damped[t]));
    }
  }
}

TEST_CASE("Measuring the work the threads share changes no bit, and counts it as the threads "
          "would take it",
          "[impulse_damped][determinism][threads]") {
  // The fast clump and the frictional one on one thread, every shareable pass counted
  // (parallelContacts and parallelNarrowPhases 0), with the measure on and off.
  const int steps = static_cast<int>(std::max(30L, testing::scaledCount(60)));
  for (const World& start : {fastClump(), frictionalClump()}) {
    std::vector<double> states[2];
    DampedStepProfile profiles[2];
    long passTests = 0;
    for (int measure = 0; measure < 2; ++measure) {
      DampedIntegrationParams params;
      params.impulse.parallelContacts = 0;
      params.impulse.parallelNarrowPhases = 0;
      DampedIntegrationStepper stepper(params);
      profiles[measure].measureParallelWork = measure == 1;
      stepper.setProfile(&profiles[measure]);
      World world = start;
      for (int k = 0; k < steps; ++k) {
        stepper.step(world, 1.0 / 60.0);
        appendStates(world, states[measure]);
      }
      passTests = stepper.gathering().passNarrowPhases() + stepper.gathering().passAxisChecks();
    }
    CHECK(sameBits(states[0], states[1]));
    const ParallelWork& off = profiles[0].parallelWork;
    CHECK(off.testRounds[0] == 0);
    CHECK(off.levelRounds[0] == 0);
    CHECK(off.keptRounds[0] == 0);
    const ParallelWork& work = profiles[1].parallelWork;
    // On one thread a loop of n items is n rounds; on N threads ceil(n / N) of each loop, so
    // at least the items over N, and never more than on fewer threads.
    REQUIRE(work.testRounds[0] > 0);
    REQUIRE(work.levelRounds[0] > 0);
    REQUIRE(work.keptRounds[0] > 0);
    for (std::size_t i = 1; i < ParallelWork::threadCounts.size(); ++i) {
      const long n = ParallelWork::threadCounts[i];
      CHECK(work.testRounds[i] * n >= work.testRounds[0]);
      CHECK(work.levelRounds[i] * n >= work.levelRounds[0]);
      CHECK(work.keptRounds[i] * n >= work.keptRounds[0]);
      CHECK(work.testRounds[i] <= work.testRounds[i - 1]);
      CHECK(work.levelRounds[i] <= work.levelRounds[i - 1]);
      CHECK(work.keptRounds[i] <= work.keptRounds[i - 1]);
    }
    // The narrow phases counted are the passes' own.
    CHECK(work.testRounds[0] == passTests);
    CHECK(work.testSeconds > 0.0);
    CHECK(work.levelSeconds > 0.0);
    CHECK(work.keptSeconds > 0.0);
    // The kept narrow phases of the step's start and FIXCONTACTCONSTRAINTS are counted: two
    // rounds a batch, each of at most its requests: tests run, handed back or settled by one axis.
    CHECK(work.keptRounds[0] <= 2 * (profiles[1].narrowPhases + profiles[1].keptNarrowPhases +
                                     profiles[1].axisChecks));
    // COLLIDE's levels hold fewer contacts than the passes' loops: a level is a loop.
    CHECK(work.levelRounds.back() < work.levelRounds[0]);
  }
}

TEST_CASE("Threads must be at least one", "[impulse_damped][threads]") {
  DampedIntegrationParams params;
  params.impulse.threads = 0;
  CHECK_THROWS_WITH(DampedIntegrationStepper(params), Catch::Contains("threads must be >= 1"));
  ImpulseStepperParams plain;
  plain.impulse.threads = 0;
  CHECK_THROWS_WITH(ImpulseStepper(plain), Catch::Contains("threads must be >= 1"));
}
