// Verification of two basic techniques added to damped integration: sleeping bodies at rest
// (computational stability, thesis §4.5) and randomly perturbed high-speed collisions (visual
// plausibility, §4.2). Sleeping: a body falls asleep after coming to rest, stays asleep, wakes
// when hit and moves, holds what lands on it, and makes a resting pile cost (almost) nothing.
// Plausibility: reproducible from its seed, different across seeds, and never touching slow
// collisions or contacts.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "boxsim/collision/separating_axis.hpp"
#include "boxsim/impulse_damped/chatter_history.hpp"
#include "boxsim/impulse_damped/damped_integration.hpp"
#include "boxsim/impulse_damped/dampen_objects.hpp"
#include "boxsim/impulse_damped/visual_plausibility.hpp"
#include "boxsim/io/scene.hpp"
#include "boxsim/io/scene_builders.hpp"
#include "boxsim/io/simulate.hpp"
#include "test_worlds.hpp"

using namespace boxsim;
using boxsim::testing::groundWorld;

namespace {

constexpr double kDt = 1.0 / 60.0;
/// Steps a body must stay still before it sleeps, with the default parameters at 60 Hz.
const long kStepsToSleep = std::lround(SleepParams{}.timeToSleep / kDt);
/// The FIXCONTACTCONSTRAINTS slop for unit cubes (ℓ = 0.5 m), m.
const double kSlop = FixContactParams{}.slop * 0.5;

/// A unit cube (ℓ = 0.5 m, h = √0.75 m) at `x`, rotated by `angle` rad about z, moving at `v`.
RigidBody cubeAt(const Vec3& x, double angle = 0.0, const Vec3& v = Vec3::Zero()) {
  RigidBody b = RigidBody::box(Vec3::Constant(0.5), 1.0);
  b.s.x = x;
  b.s.q = Quat(Eigen::AngleAxisd(angle, Vec3::UnitZ()));
  b.updateDerived();
  b.setVelocity(v);
  return b;
}

/// Adds a unit cube (1 kg) at `centre` with velocity `v`; returns its index.
int addCube(World& world, const Vec3& centre, const Vec3& v = Vec3::Zero()) {
  return world.add(cubeAt(centre, 0.0, v), "cube" + std::to_string(world.bodies.size()));
}

int countAsleep(const DampedIntegrationStepper& stepper) {
  return static_cast<int>(std::count(stepper.asleep().begin(), stepper.asleep().end(), 1));
}

/// Steps until every movable body sleeps; returns the step count, or -1 after `limit` steps.
int stepUntilAsleep(World& world, DampedIntegrationStepper& stepper, int limit) {
  for (int k = 1; k <= limit; ++k)
    if (stepper.step(world, kDt).sleeping == world.movableCount()) return k;
  return -1;
}

double depth(const World& world, int i, int j) {
  return separatingAxisTest(Obb::of(world.bodies[i]), Obb::of(world.bodies[j])).depth;
}

DampedIntegrationParams plausible(unsigned long seed) {
  DampedIntegrationParams params;
  params.plausibility.enabled = true;
  params.plausibility.seed = seed;
  return params;
}

/// The die of §4.2 thrown at the ground: it lands at about 8 m/s, far above the 2 m/s
/// threshold of visual plausibility.
World thrownDie() {
  World world = groundWorld();
  addDie(world, DieSpec{1.0, 1.0, Vec3(0.0, 2.0, 0.0), 10.0, Vec3(1.0, 0.0, 1.0),
                        Vec3(1.0, -6.0, 0.0), Vec3(0.0, 1.0, 0.0)});
  return world;
}

WorldState run(World world, const DampedIntegrationParams& params, int steps,
               long* perturbations = nullptr) {
  DampedIntegrationStepper stepper(params);
  for (int k = 0; k < steps; ++k) stepper.step(world, kDt);
  if (perturbations) *perturbations = stepper.plausibility().perturbations();
  return world.saveState();
}

}  // namespace

// --- sleeping (§4.5) ----------------------------------------------------------------------

TEST_CASE("A dropped die falls asleep once it has been still for the sleep time, and stays asleep",
          "[impulse_damped][sleeping]") {
  World world = groundWorld();
  addDie(world, DieSpec{});
  DampedIntegrationStepper stepper;
  // The step from which the die is exactly still (momenta zero, pose unchanged) for good, and
  // the step it falls asleep.
  int stillFrom = -1, asleepAt = -1;
  BodyState previous = world.bodies[1].s;
  for (int k = 1; k <= 8 * 60 && asleepAt < 0; ++k) {
    const StepStats stats = stepper.step(world, kDt);
    const BodyState& s = world.bodies[1].s;
    const bool still = s.P == Vec3::Zero() && s.L == Vec3::Zero() && s.x == previous.x &&
                       s.q.coeffs() == previous.q.coeffs();
    if (!still) stillFrom = -1;
    else if (stillFrom < 0) stillFrom = k;
    previous = s;
    if (stats.sleeping == 1) asleepAt = k;
  }
  INFO("still from step " << stillFrom << ", asleep at step " << asleepAt);
  REQUIRE(asleepAt > 0);
  // Bounded: the die must rest within 60 % of the undamped Zeno time (impulse_damped_test),
  // 6.3 s, and then sleeps after exactly the sleep time of stillness.
  CHECK(asleepAt * kDt < 0.6 * 19.0 * std::sqrt(2.0 * 1.5 / 9.81) + SleepParams{}.timeToSleep);
  CHECK(asleepAt - stillFrom + 1 == kStepsToSleep);
  // Asleep for 5 s more, bit for bit where it fell asleep.
  const BodyState slept = world.bodies[1].s;
  for (int k = 0; k < 5 * 60; ++k) {
    const StepStats stats = stepper.step(world, kDt);
    REQUIRE(stats.sleeping == 1);
    REQUIRE(stepper.asleep()[1] == 1);
  }
  CHECK(world.bodies[1].s == slept);
}

TEST_CASE("A sleeping box wakes when another box slides into it, and the hit moves it",
          "[impulse_damped][sleeping]") {
  World world = groundWorld();
  const int resting = addCube(world, Vec3(0.0, 0.5, 0.0));
  DampedIntegrationStepper stepper;
  REQUIRE(stepUntilAsleep(world, stepper, 120) > 0);
  const Vec3 x0 = world.bodies[resting].s.x;
  // Slides in from 0.6 m away at 3 m/s; damping slows it to about 1.2 m/s at the impact,
  // above the wake speed of 4 g Δt = 0.65 m/s.
  const int slider = addCube(world, Vec3(1.6, 0.5, 0.0), Vec3(-3.0, 0.0, 0.0));
  int wokeAt = -1;
  for (int k = 1; k <= 60 && wokeAt < 0; ++k) {
    stepper.step(world, kDt);
    if (!stepper.asleep()[resting]) wokeAt = k;
  }
  INFO("woke at step " << wokeAt);
  REQUIRE(wokeAt > 0);
  // It was hit in the step it woke, so it has taken the impulse: it moves away from the slider,
  // which has given it most of its momentum (restitution 0.9 between equal masses).
  CHECK(world.bodies[resting].v.x() < -0.5);
  CHECK(world.bodies[resting].v.x() < world.bodies[slider].v.x());
  for (int k = 0; k < 60; ++k) stepper.step(world, kDt);
  const double moved = (world.bodies[resting].s.x - x0).norm();
  INFO("the hit box moved " << moved << " m");
  CHECK(moved > 0.1);
  // Both come to rest again and sleep.
  CHECK(stepUntilAsleep(world, stepper, 5 * 60) > 0);
  CHECK(countAsleep(stepper) == 2);
}

TEST_CASE("A sleeping box hit hard from above wakes only itself, the boxes under it hold",
          "[impulse_damped][sleeping]") {
  // A box dropped 0.5 m onto a sleeping tower lands at 3.1 m/s: it wakes the top box, which
  // rests on sleeping boxes that hold it like the ground; nothing below the top box wakes.
  World world = groundWorld();
  addTower(world, TowerSpec{10});
  DampedIntegrationStepper stepper;
  REQUIRE(stepUntilAsleep(world, stepper, 120) > 0);
  const WorldState before = world.saveState();
  const int box = addCube(world, Vec3(0.1, 11.0, 0.05));
  int mostAwake = 0;
  bool topWoke = false;
  for (int k = 0; k < 4 * 60; ++k) {
    stepper.step(world, kDt);
    mostAwake = std::max(mostAwake, world.movableCount() - countAsleep(stepper));
    topWoke = topWoke || !stepper.asleep()[10];
    REQUIRE(depth(world, box, 10) <= kSlop + 1e-12);
  }
  CHECK(topWoke);
  CHECK(mostAwake == 2);
  for (int i = 1; i <= 9; ++i) CHECK(world.bodies[i].s == before.bodies[i]);
  CHECK(countAsleep(stepper) == 11);
}

TEST_CASE("A sleeping tower of 10 stays put and supports a box set down on it within the slop",
          "[impulse_damped][sleeping]") {
  World world = groundWorld();
  addTower(world, TowerSpec{10});
  DampedIntegrationStepper stepper;
  REQUIRE(stepUntilAsleep(world, stepper, 120) > 0);
  const WorldState before = world.saveState();
  // Set down from 1 cm: it lands at 0.44 m/s, under the wake speed.
  const int box = addCube(world, Vec3(0.1, 10.51, 0.05));
  double deepest = -1.0;
  for (int k = 0; k < 3 * 60; ++k) {
    stepper.step(world, kDt);
    deepest = std::max(deepest, depth(world, box, 10));
    REQUIRE(countAsleep(stepper) >= 10);  // the tower never wakes
  }
  INFO("deepest penetration of the new box into the tower " << deepest << " m");
  CHECK(deepest <= kSlop + 1e-12);
  // Resting on the top box (centre 9.5 m): not sunk, not hovering beyond g Δt².
  CHECK(world.bodies[box].s.x.y() >= 10.5 - kSlop);
  CHECK(world.bodies[box].s.x.y() <= 10.5 + 9.81 * kDt * kDt);
  for (int i = 1; i <= 10; ++i) CHECK(world.bodies[i].s == before.bodies[i]);
  // It settles and falls asleep on the tower.
  CHECK(stepper.asleep()[box] == 1);
}

TEST_CASE("A fully asleep pyramid of base 10 applies no impulses, awake it applies over 1000 a step",
          "[impulse_damped][sleeping][cost]") {
  StepStats last[2];
  for (int sleep = 0; sleep < 2; ++sleep) {
    World world = groundWorld();
    addPyramid(world, PyramidSpec{10});
    DampedIntegrationParams params;
    params.sleep.enabled = sleep == 1;
    DampedIntegrationStepper stepper(params);
    for (int k = 0; k < 60; ++k) stepper.step(world, kDt);
    StepStats sum;
    for (int k = 0; k < 60; ++k) sum += stepper.step(world, kDt);
    last[sleep] = sum;
  }
  INFO("impulses in the second second: awake " << last[0].events << ", asleep " << last[1].events);
  CHECK(last[1].sleeping == 55);
  CHECK(last[1].events == 0);
  CHECK(last[0].sleeping == 0);
  CHECK(last[0].events > 1000 * 60);
  // Every contact still counts as touching, remembered from the step the pyramid fell asleep.
  CHECK(last[1].contacts == last[0].contacts);
}

TEST_CASE("A sleeping pyramid costs an awake box nothing: its impulses and path are its own alone",
          "[impulse_damped][sleeping][cost]") {
  // The broad phase drops sleeping pairs and the narrow phase sees only the box: the box's
  // steps, impulses included, are bit for bit those of the box in an empty world.
  World alone = groundWorld();
  addDie(alone, DieSpec{1.0, 1.0, Vec3(20.0, 2.0, 0.0)});
  World beside = groundWorld();
  addPyramid(beside, PyramidSpec{10});
  DampedIntegrationStepper aloneStepper, besideStepper;
  REQUIRE(stepUntilAsleep(beside, besideStepper, 120) > 0);
  addDie(beside, DieSpec{1.0, 1.0, Vec3(20.0, 2.0, 0.0)});
  for (int k = 0; k < 3 * 60; ++k) {
    const StepStats a = aloneStepper.step(alone, kDt);
    const StepStats b = besideStepper.step(beside, kDt);
    REQUIRE(a.events == b.events);
    REQUIRE(b.sleeping >= 55);
    REQUIRE(alone.bodies[1].s == beside.bodies.back().s);
  }
}

TEST_CASE("Sleeping changes cost, not outcome, for a scene that comes to rest undisturbed",
          "[impulse_damped][sleeping][determinism]") {
  for (int scene = 0; scene < 2; ++scene) {
    WorldState end[2];
    for (int sleep = 0; sleep < 2; ++sleep) {
      World world = groundWorld();
      if (scene == 0) addDie(world, DieSpec{});
      else addTower(world, TowerSpec{10});
      DampedIntegrationParams params;
      params.sleep.enabled = sleep == 1;
      end[sleep] = run(world, params, 8 * 60);
    }
    INFO("scene " << (scene == 0 ? "die" : "tower"));
    CHECK(end[0] == end[1]);
  }
}

TEST_CASE("A sleeping box kicked from outside the stepper wakes, and so does the box it carries",
          "[impulse_damped][sleeping]") {
  World world = groundWorld();
  addTower(world, TowerSpec{2});
  DampedIntegrationStepper stepper;
  REQUIRE(stepUntilAsleep(world, stepper, 120) > 0);
  const Vec3 top0 = world.bodies[2].s.x;
  // Fast enough to slide out from under the (frictionless) top box against the damping.
  world.bodies[1].setVelocity(Vec3(6.0, 0.0, 0.0));
  stepper.step(world, kDt);
  CHECK(stepper.asleep()[1] == 0);
  CHECK(world.bodies[1].s.x.x() > 0.0);
  // The top box lost its support's guarantee to stay put: it is awake, and falls.
  CHECK(stepper.asleep()[2] == 0);
  for (int k = 0; k < 90; ++k) stepper.step(world, kDt);
  CHECK(world.bodies[2].s.x.y() < top0.y() - 0.1);
}

TEST_CASE("A box asleep on an immovable support wakes when the support is made movable",
          "[impulse_damped][sleeping]") {
  // What World::applyLaunches does to a body that waited immovable for its launch.
  World world = groundWorld();
  RigidBody pedestal = RigidBody::immovableBox(Vec3::Constant(0.5));
  pedestal.s.x = Vec3(0.0, 0.5, 0.0);
  pedestal.updateDerived();
  const int support = world.add(pedestal, "pedestal");
  const int box = addCube(world, Vec3(0.0, 1.5, 0.0));
  DampedIntegrationStepper stepper;
  REQUIRE(stepUntilAsleep(world, stepper, 120) > 0);
  RigidBody launched = RigidBody::box(Vec3::Constant(0.5), 1.0);
  launched.s.x = pedestal.s.x;
  launched.updateDerived();
  launched.setVelocity(Vec3(5.0, 0.0, 0.0));
  world.bodies[support] = launched;
  stepper.step(world, kDt);
  CHECK(stepper.asleep()[box] == 0);
}

// --- chatter detected from history (§6.3.1) -------------------------------------------------

TEST_CASE("Chatter history: a window within the envelope, not sinking, its energy not growing, "
          "chatters, and leaving the envelope, sinking or gathering energy does not",
          "[impulse_damped][sleeping][chatter]") {
  // A unit cube: envelope r = 0.05 ℓ = 2.5 cm for the centre, r / h = 0.0289 rad for the turn;
  // slop 0.001 ℓ = 0.5 mm of sinking; a window of 30 steps; g = 9.81 m/s² down.
  const Vec3 g(0.0, -9.81, 0.0);
  const long window = 30;
  const auto runWith = [&](auto poseAt, auto speedAt) {
    ChatterHistory history(0.05, 0.001);
    history.resize(1);
    for (long k = 0; k < window; ++k) {
      RigidBody b = cubeAt(Vec3::Zero(), 0.0, Vec3(speedAt(k), 0.0, 0.0));
      b.s.x = poseAt(k).first;
      b.s.q = Quat(Eigen::AngleAxisd(poseAt(k).second, Vec3::UnitZ()));
      b.updateDerived();
      history.record(0, b, g, window);
      if (k < window - 1) REQUIRE_FALSE(history.chatters(0));  // not a full window yet
    }
    return history.chatters(0);
  };
  const auto still = [](long) { return std::pair<Vec3, double>(Vec3::Zero(), 0.0); };
  const auto steady = [](long) { return 0.01; };  // m/s, a kick that goes nowhere
  // Held in place with a steady small speed: chatter.
  CHECK(runWith(still, steady));
  // Rocking within the envelope (±2 cm, ±0.02 rad) with decaying energy: chatter.
  CHECK(runWith([](long k) { return std::pair<Vec3, double>(Vec3(k % 2 ? 0.02 : -0.0, 0.0, 0.0),
                                                            k % 2 ? 0.02 : 0.0); },
                [](long k) { return 0.1 / (1.0 + k); }));
  // Drifting 3 cm over the window: beyond the envelope.
  CHECK_FALSE(runWith([](long k) { return std::pair<Vec3, double>(Vec3(0.001 * k, 0.0, 0.0), 0.0); },
                      steady));
  // Turning 0.035 rad: beyond the envelope's 0.0289.
  CHECK_FALSE(runWith([](long k) { return std::pair<Vec3, double>(Vec3::Zero(), 0.035 * k / 29.0); },
                      steady));
  // Sinking 1 mm (twice the slop) while tipping slowly, energy held level by damping: gravity
  // works on it, not chatter.
  CHECK_FALSE(runWith([](long k) { return std::pair<Vec3, double>(Vec3(0.0, -0.001 * k / 29.0, 0.0),
                                                                  0.0); },
                      steady));
  // Sinking 0.4 mm, within the slop: a contact settling, still chatter.
  CHECK(runWith([](long k) { return std::pair<Vec3, double>(Vec3(0.0, -0.0004 * k / 29.0, 0.0), 0.0); },
                steady));
  // Gathering energy (a fall beginning): speed growing through the window.
  CHECK_FALSE(runWith(still, [](long k) { return 0.001 * k; }));
}

TEST_CASE("Chatter detection puts the clump's chattering cubes to sleep: the heap comes to rest, "
          "every cube asleep, where sleeping alone leaves it awake for ever",
          "[impulse_damped][sleeping][chatter][clump]") {
  // clump100_ground.json (Fig. 6.7 read with the origin on the ground): with sleeping alone,
  // some cubes keep small momenta for ever (impulse_damped_test), so the heap never sleeps.
  Scene scene =
      loadScene(std::string(BOXSIM_SOURCE_DIR) + "/chapters/impulse_damped/scenes/clump100_ground.json");
  World& world = scene.world;
  DampedIntegrationParams params;
  params.sleep.chatterDetection = true;
  DampedIntegrationStepper stepper(params);
  const int asleepAt = stepUntilAsleep(world, stepper, 10 * 60);
  INFO("every cube asleep at step " << asleepAt);
  REQUIRE(asleepAt > 0);
  // At rest for good: 2 s more without a bit of change, the kinetic energy exactly 0.
  const WorldState rested = world.saveState();
  for (int k = 0; k < 2 * 60; ++k) stepper.step(world, kDt);
  CHECK(world.saveState() == rested);
  CHECK(world.kineticEnergy() == 0.0);
  // Put to rest as they chattered, not frozen mid-fall: every cube lies with a face down
  // (DAMPENOBJECTS' aligned test, 3°) and the heap is the heap of impulse_damped_test (at
  // least four layers, more compact than a cone of the cubes' volume 4 m high).
  for (const RigidBody& b : world.bodies)
    if (!b.immovable) CHECK(isYAxisAligned(b, DampingParams{}.alignedAngleDeg));
  const boxsim::testing::HeapMeasure heap = boxsim::testing::measureHeap(world, 100.0, 4.0);
  CHECK(heap.rmsRadius < heap.coneRmsRadius);
  CHECK(heap.beyondCone <= heap.count / 20);
  CHECK(heap.top > 3.5);
}

TEST_CASE("Chatter detection never fires on a box tipping off an edge, a box falling or one "
          "drifting in space, whose runs are bit for bit the runs without it",
          "[impulse_damped][sleeping][chatter]") {
  const auto both = [](World world, int steps) {
    DampedIntegrationParams with;
    with.sleep.chatterDetection = true;
    return std::pair<WorldState, WorldState>(run(world, {}, steps), run(world, with, steps));
  };
  SECTION("a cube tilted 30° on an edge topples flat") {
    // Its centre is beyond its edge of support from the start: gravity does work on it all
    // along (the sinking test).
    World world = groundWorld();
    world.add(cubeAt(Vec3(0.0, 0.5 * std::sqrt(2.0) * std::cos(kPi / 12.0), 0.0), kPi / 6.0), "tipping");
    const auto [without, with] = both(world, 3 * 60);
    CHECK(with == without);
    World after = world;
    after.restoreState(with);
    CHECK(isYAxisAligned(after.bodies[1], DampingParams{}.alignedAngleDeg));
  }
  SECTION("a cube dropped from 2 m lands, bounces and comes to rest exactly still") {
    World world = groundWorld();
    world.add(cubeAt(Vec3(0.0, 2.0, 0.0)), "dropped");
    const auto [without, with] = both(world, 4 * 60);
    CHECK(with == without);
  }
  SECTION("a cube drifting at 1 cm/s in space, nothing to chatter on, keeps its momentum") {
    World world = boxsim::testing::spaceWorld();
    world.add(cubeAt(Vec3::Zero(), 0.0, Vec3(0.01, 0.0, 0.0)), "drifting");
    const auto [without, with] = both(world, 2 * 60);
    CHECK(with == without);
    World after = world;
    after.restoreState(with);
    CHECK(after.bodies[0].s.P.x() == 0.01);
  }
}

// --- visual plausibility (§4.2) ------------------------------------------------------------

TEST_CASE("Perturbed normals stay unit and within the largest angle, slow ones are untouched",
          "[impulse_damped][plausibility]") {
  PlausibilityParams params;
  params.enabled = true;
  VisualPlausibility plausibility(params);
  const double maxAngle = params.maxAngleDeg * kPi / 180.0;
  double largest = 0.0, sum = 0.0;
  const int draws = 20000;
  for (int k = 0; k < draws; ++k) {
    ImpulseContact c;
    c.normal = Vec3(std::sin(0.001 * k), std::cos(0.001 * k), 0.3).normalized();
    const Vec3 before = c.normal;
    // Slow: untouched, and no number drawn.
    REQUIRE_FALSE(plausibility.perturb(c, params.speedThreshold));
    REQUIRE(c.normal == before);
    REQUIRE(plausibility.perturb(c, params.speedThreshold + 0.1));
    REQUIRE(std::abs(c.normal.norm() - 1.0) < 1e-12);
    const double angle = std::acos(std::min(1.0, c.normal.dot(before)));
    largest = std::max(largest, angle);
    sum += angle;
  }
  CHECK(plausibility.perturbations() == draws);
  CHECK(largest <= maxAngle + 1e-9);
  // Uniform over the cap: for a small cap the angle's density grows like θ, so its mean is
  // (2/3) θmax; the largest of 20000 draws comes within 1 % of θmax.
  CHECK(sum / draws == Approx(2.0 / 3.0 * maxAngle).epsilon(0.02));
  CHECK(largest > 0.99 * maxAngle);
  // A copy continues the same stream.
  VisualPlausibility copy = plausibility;
  ImpulseContact a, b;
  plausibility.perturb(a, 10.0);
  copy.perturb(b, 10.0);
  CHECK(a.normal == b.normal);
}

TEST_CASE("Visual plausibility: the same seed gives bit-identical runs, another seed another path",
          "[impulse_damped][plausibility][determinism]") {
  long perturbed = 0;
  const WorldState first = run(thrownDie(), plausible(7), 2 * 60, &perturbed);
  const WorldState again = run(thrownDie(), plausible(7), 2 * 60);
  const WorldState otherSeed = run(thrownDie(), plausible(8), 2 * 60);
  const WorldState off = run(thrownDie(), DampedIntegrationParams{}, 2 * 60);
  INFO("normals perturbed " << perturbed);
  CHECK(perturbed > 0);
  CHECK(first == again);
  CHECK_FALSE(first == otherSeed);
  CHECK_FALSE(first == off);
  // Visibly different, not by rounding: the seeds part the die by more than a millimetre.
  CHECK((first.bodies[1].x - otherSeed.bodies[1].x).norm() > 1e-3);
}

TEST_CASE("Visual plausibility never perturbs slow collisions or resting contacts",
          "[impulse_damped][plausibility]") {
  // A tower at rest (contacts only) and a level cube dropped from 10 cm (landing flat at
  // 1.4 m/s, under the 2 m/s threshold): with perturbation on they are bit for bit what they
  // are with it off. (A tilted die dropped from 10 cm does not qualify: its first corner lands
  // at 1.4 m/s, but the spin that impact gives it brings the opposite edge down at 3 m/s.)
  for (int scene = 0; scene < 2; ++scene) {
    World world = groundWorld();
    if (scene == 0) addTower(world, TowerSpec{10});
    else addCube(world, Vec3(0.0, 0.6, 0.0));
    long perturbed = -1;
    const WorldState on = run(world, plausible(7), 3 * 60, &perturbed);
    const WorldState off = run(world, DampedIntegrationParams{}, 3 * 60);
    INFO("scene " << (scene == 0 ? "tower" : "slow cube"));
    CHECK(perturbed == 0);
    CHECK(on == off);
  }
}

TEST_CASE("The plausibility seed is written into the run header and wins over the default",
          "[impulse_damped][plausibility][io]") {
  const World world = groundWorld();
  const DampedIntegrationStepper seeded(plausible(42));
  CHECK(seeded.parameters().at("seed") == "42");
  CHECK(runParameters(seeded, world, "scene.json", kDt, 1.0).at("seed") == "42");
  const DampedIntegrationStepper defaults;
  CHECK(runParameters(defaults, world, "scene.json", kDt, 1.0).at("seed") ==
        std::to_string(PlausibilityParams{}.seed));
}
