// Contact gathering at predicted positions (contact_gathering.hpp): the once-per-step cache
// against Alg. A.2 as written, which runs the narrow phase at the predicted poses every pass.
#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "boxsim/collision/contact_manifold.hpp"
#include "boxsim/impulse_damped/contact_gathering.hpp"
#include "boxsim/impulse_damped/damped_integration.hpp"
#include "boxsim/impulse_damped/impulse_pass.hpp"
#include "boxsim/impulse_damped/impulse_stepper.hpp"
#include "boxsim/io/scene.hpp"
#include "seeded_random.hpp"
#include "test_worlds.hpp"

using namespace boxsim;
using boxsim::testing::SeededRandom;
using boxsim::testing::groundWorld;

namespace {

constexpr double kDt = 1.0 / 60.0;
constexpr double kMargin = 5e-4;  // m: ImpulseParams::contactMargin times ℓ = 0.5 m

ImpulseParams gatheringParams(ContactGatheringMode mode) {
  ImpulseParams p;
  p.gathering = mode;
  p.normalModel = ContactNormalModel::SeparatingAxis;  // no memory between calls
  return p;
}

/// Pair -> depth of the contacts one pass gathers, each gathering on its own copy of the world.
std::map<std::pair<int, int>, double> gathered(World world, ContactGathering& gathering,
                                               GravityMode predict) {
  std::map<std::pair<int, int>, double> found;
  for (const ImpulseContact& c : gathering.begin(world, kDt, predict, kMargin))
    found[{c.a, c.b}] = c.depth;
  gathering.end(world);
  return found;
}

/// Twelve unit cubes in a 3 m box above the ground, a third of them fast (up to 8 m/s and
/// 6 rad/s, several contacts' worth of motion per step), the rest slow.
World randomScene(SeededRandom& random) {
  World world = groundWorld();
  for (int i = 0; i < 12; ++i) {
    RigidBody box = RigidBody::box(Vec3::Constant(0.5), 1.0);
    box.s.x = Vec3(random.uniform(-1.5, 1.5), random.uniform(0.3, 3.0), random.uniform(-1.5, 1.5));
    box.s.q = random.rotation();
    const bool fast = i % 3 == 0;
    box.s.P = random.vector(-1.0, 1.0) * (fast ? 8.0 : 0.3);
    box.updateDerived();
    box.setAngularVelocity(random.vector(-1.0, 1.0) * (fast ? 6.0 : 0.3));
    world.bodies.push_back(box);
    world.names.push_back("box" + std::to_string(i));
  }
  return world;
}

}  // namespace

TEST_CASE("Once-per-step gathering finds every pair the exact prediction finds, pass after pass",
          "[impulse_damped][contact_gathering][reference]") {
  // What the two may disagree on: a slow pair's depth by the Taylor remainder (below 1e-7 m
  // here). Pairs within that band of the margin may fall either way; every other pair must be
  // found by both, a fast body and its slow partner too (both are moved for their narrow phase).
  // The same with the predicted anchor (ImpulseParams::predictedAnchor): there the fast bodies
  // are cached where the first pass predicts them, and a pass whose prediction moved from there
  // by g Δt² (the passes without gravity) or by a kick is predicted or gathered exactly.
  const double band = 1e-7;
  for (const bool anchor : {false, true}) {
  INFO("predicted anchor " << anchor);
  SeededRandom random(20261121);
  int compared = 0;
  for (int scene = 0; scene < 40; ++scene) {
    World world = randomScene(random);
    ContactGathering exact(gatheringParams(ContactGatheringMode::EveryPass));
    ImpulseParams cachedParams = gatheringParams(ContactGatheringMode::OncePerStep);
    cachedParams.predictedAnchor = anchor;
    ContactGathering cached(cachedParams);
    for (int pass = 0; pass < 4; ++pass) {
      const GravityMode predict = pass % 2 ? GravityMode::VelocityNoGravity
                                           : GravityMode::VelocityPlusGravity;
      const auto reference = gathered(world, exact, predict);
      const auto fast = gathered(world, cached, predict);
      for (const auto& [pair, depth] : reference)
        if (depth > -kMargin + band) {
          INFO("scene " << scene << " pass " << pass << " pair " << pair.first << "-" << pair.second
                        << " exact depth " << depth);
          CHECK(fast.count(pair) == 1);
          ++compared;
        }
      for (const auto& [pair, depth] : fast)
        if (depth > -kMargin + band) {
          INFO("scene " << scene << " pass " << pass << " pair " << pair.first << "-" << pair.second
                        << " predicted depth " << depth);
          CHECK(reference.count(pair) == 1);
        }
      // Between passes impulses change velocities: kick one body hard, so the cache must notice
      // that its widened margin no longer covers that body's reach.
      RigidBody& kicked = world.bodies[1 + random.integer(0, 11)];
      kicked.s.P = random.vector(-1.0, 1.0) * 15.0;
      kicked.updateVelocities();
    }
  }
  INFO(compared << " pairs compared");
  CHECK(compared > 100);
  }
}

TEST_CASE("For slow bodies the Taylor prediction matches the moved pose to its remainder",
          "[impulse_damped][contact_gathering][reference]") {
  // A cube on the ground, tilted a little and turning slowly: its four lower corners are the
  // contact points either way (the ground face is far larger), so the deepest predicted depth
  // must agree with the narrow phase at the moved pose to the Taylor remainder
  // Δt³ |ω|³ ρ / 6 plus the quaternion step's own O(Δt³ |ω|³) error, both below 1e-6 m here.
  SeededRandom random(7);
  for (int k = 0; k < 200; ++k) {
    World world = groundWorld();
    RigidBody box = RigidBody::box(Vec3::Constant(0.5), 1.0);
    box.s.q = Quat(Eigen::AngleAxisd(random.uniform(-0.05, 0.05), random.vector(-1, 1).normalized()));
    box.s.x = Vec3(random.uniform(-1, 1), 0.5 + random.uniform(-2e-3, 2e-3), random.uniform(-1, 1));
    box.updateDerived();
    box.setVelocity(random.vector(-0.2, 0.2));
    box.setAngularVelocity(random.vector(-0.3, 0.3));
    world.bodies.push_back(box);
    world.names.push_back("box");
    ContactGathering cached(gatheringParams(ContactGatheringMode::OncePerStep));
    ContactGathering exact(gatheringParams(ContactGatheringMode::EveryPass));
    const auto fast = gathered(world, cached, GravityMode::VelocityPlusGravity);
    const auto reference = gathered(world, exact, GravityMode::VelocityPlusGravity);
    const std::pair<int, int> pair(0, 1);
    REQUIRE(fast.count(pair) == reference.count(pair));
    if (!reference.count(pair)) continue;
    INFO("case " << k);
    CHECK(std::abs(fast.at(pair) - reference.at(pair)) < 1e-6);
  }
}

TEST_CASE("Both gatherings give the same bounce of a dropped cube", "[impulse_damped][contact_gathering]") {
  // A cube dropped flat from 1 m is fast when it hits (exact narrow phase either way) and slow
  // when it rests; its rebound apex must agree to rounding, and both rest at the same height.
  double apex[2] = {0.0, 0.0}, rest[2] = {0.0, 0.0};
  for (int mode = 0; mode < 2; ++mode) {
    World world = groundWorld();
    RigidBody box = RigidBody::box(Vec3::Constant(0.5), 1.0);
    box.s.x = Vec3(0.0, 1.5, 0.0);
    box.updateDerived();
    world.bodies.push_back(box);
    world.names.push_back("box");
    ImpulseStepperParams params;
    params.impulse.gathering = mode ? ContactGatheringMode::OncePerStep : ContactGatheringMode::EveryPass;
    ImpulseStepper stepper(params);
    bool rising = false;
    for (int k = 0; k < 240; ++k) {
      stepper.step(world, kDt);
      const RigidBody& b = world.bodies[1];
      if (b.v.y() > 0.0) rising = true;
      if (rising && apex[mode] == 0.0 && b.v.y() <= 0.0) apex[mode] = b.s.x.y();
    }
    rest[mode] = world.bodies[1].s.x.y();
  }
  INFO("apex " << apex[0] << " / " << apex[1] << " m, rest " << rest[0] << " / " << rest[1] << " m");
  CHECK(apex[0] > 0.5);
  CHECK(apex[1] == Approx(apex[0]).margin(1e-9));
  CHECK(rest[1] == Approx(rest[0]).margin(1e-3));
}

TEST_CASE("A slow box on a fast thin plate is gathered as every-pass gathering finds it",
          "[impulse_damped][contact_gathering][reference]") {
  // A plate 2 cm thick (ℓ = 1 cm) resting on the ground is fast under gravity alone: it moves
  // g Δt² = 2.7 mm in a pass, more than exactReach ℓ = 0.2 mm. The box on it (ℓ = 25 cm),
  // sliding and turning a little, is slow: it moves 4 mm, under exactReach ℓ = 5 mm. Its
  // contact with the plate is found only if both are looked at where the pass predicts them:
  // with the plate moved and the box left where it stands, the two are 2.7 mm apart, more than
  // the margin. Moved both, the pair's narrow phase is the every-pass one, so the contact must
  // agree exactly: same pairs, depths, points and normals.
  World world = groundWorld();
  RigidBody plate = RigidBody::box(Vec3(0.5, 0.01, 0.5), 2.0);
  plate.s.x = Vec3(0.0, 0.01, 0.0);
  plate.updateDerived();
  world.bodies.push_back(plate);
  world.names.push_back("plate");
  RigidBody box = RigidBody::box(Vec3::Constant(0.25), 1.0);
  box.s.x = Vec3(0.05, 0.02 + 0.25, -0.03);
  box.updateDerived();
  box.setVelocity(Vec3(0.1, 0.0, 0.05));
  box.setAngularVelocity(Vec3(0.0, 0.1, 0.0));
  world.bodies.push_back(box);
  world.names.push_back("box");
  const double margin = ImpulseParams{}.contactMargin * 0.01;  // the damped step's, ℓ = 1 cm
  ContactGathering exact(gatheringParams(ContactGatheringMode::EveryPass));
  ContactGathering cached(gatheringParams(ContactGatheringMode::OncePerStep));
  World exactWorld = world, cachedWorld = world;
  // Passes that add g Δt, as RESOLVECOLLISIONS' do (without it the plate at rest is slow too,
  // and the pair a slow one): the first builds the step's cache, the second uses it.
  for (int pass = 0; pass < 2; ++pass) {
    const std::vector<ImpulseContact> reference =
        exact.begin(exactWorld, kDt, GravityMode::VelocityPlusGravity, margin);
    exact.end(exactWorld);
    const std::vector<ImpulseContact> found =
        cached.begin(cachedWorld, kDt, GravityMode::VelocityPlusGravity, margin);
    // The partner stands where it stood once gathering is done; only the fast plate is moved.
    CHECK(cachedWorld.bodies[2].s.x == world.bodies[2].s.x);
    CHECK(cachedWorld.bodies[2].omega == world.bodies[2].omega);
    cached.end(cachedWorld);
    INFO("pass " << pass);
    REQUIRE(reference.size() == 2);  // plate on the ground, box on the plate
    REQUIRE(found.size() == reference.size());
    for (std::size_t k = 0; k < found.size(); ++k) {
      INFO("contact " << reference[k].a << "-" << reference[k].b);
      CHECK(found[k].a == reference[k].a);
      CHECK(found[k].b == reference[k].b);
      CHECK(found[k].depth == reference[k].depth);
      CHECK(found[k].point == reference[k].point);
      CHECK(found[k].normal == reference[k].normal);
    }
  }
}

TEST_CASE("Two fast boxes moving together are predicted like slow ones",
          "[impulse_damped][contact_gathering][reference]") {
  // A cube resting on another, both flying at 8 m/s and turning slowly (ImpulseParams::pairReach):
  // each is fast on its own, moving 13 cm in a pass, but the pair's relative motion is the
  // turn alone, 0.1 rad/s, Δt |ω| ρ = 1.4 mm under exactReach ℓ = 1 cm. Its contact is
  // predicted from the cache, with no narrow phase at the passes' poses, and agrees with the
  // narrow phase there to the Taylor remainder (Δt³ |ω|³ ρ / 6, below 1e-9 m); with pairReach
  // off it is looked at there.
  World world;
  for (int k = 0; k < 2; ++k) {
    RigidBody box = RigidBody::box(Vec3::Constant(0.5), 1.0);
    box.s.x = Vec3(0.0, 3.0 + k * (1.0 - 2e-4), 0.0);
    box.updateDerived();
    box.setVelocity(Vec3(8.0, 3.0, -2.0));
    box.setAngularVelocity(Vec3(0.0, 0.1, 0.0));
    world.bodies.push_back(box);
    world.names.push_back("box" + std::to_string(k));
  }
  for (const bool together : {true, false}) {
    INFO("pairReach " << together);
    ImpulseParams params = gatheringParams(ContactGatheringMode::OncePerStep);
    params.pairReach = together;
    ContactGathering cached(params);
    ContactGathering exact(gatheringParams(ContactGatheringMode::EveryPass));
    for (int pass = 0; pass < 3; ++pass) {
      const auto reference = gathered(world, exact, GravityMode::VelocityPlusGravity);
      const auto found = gathered(world, cached, GravityMode::VelocityPlusGravity);
      REQUIRE(reference.count({0, 1}) == 1);
      REQUIRE(found.count({0, 1}) == 1);
      CHECK(std::abs(found.at({0, 1}) - reference.at({0, 1})) < 1e-9);
    }
    if (together)
      CHECK(cached.passNarrowPhases() == 0);
    else
      CHECK(cached.passNarrowPhases() > 0);
  }
}

TEST_CASE("With the predicted anchor a falling box is predicted from its first pass' pose",
          "[impulse_damped][contact_gathering][reference]") {
  // A cube falling at 3 m/s, turning at 2 rad/s, 4 cm above the ground (ImpulseParams::
  // predictedAnchor): it moves 5 cm in a pass, so from where it stands it is fast and its pair
  // with the ground gets the narrow phase at every pass' pose. Anchored where the first pass
  // predicts it, the passes' predictions move from there only as the passes change its
  // velocity: the contact is predicted from the cache, with no narrow phase in the passes, and
  // agrees with the every-pass narrow phase as long as the change stays under the slow bar
  // (exactReach ℓ = 1 cm): exactly while it is none (the first pass' own pose), to the Taylor
  // remainder after a change of 0.3 m/s and 0.3 rad/s (Δt² |δω| (|ω| + |δω|) ρ, below 2e-4 m).
  // A change of 3 m/s (sideways: it still lands) moves the prediction 5 cm from the anchor:
  // the box is fast again and its pair gets the exact narrow phase.
  World world = groundWorld();
  RigidBody box = RigidBody::box(Vec3::Constant(0.5), 1.0);
  box.s.x = Vec3(0.0, 0.54, 0.0);
  box.s.q = Quat(Eigen::AngleAxisd(0.02, Vec3(1.0, 0.0, 0.3).normalized()));
  box.updateDerived();
  box.setVelocity(Vec3(0.5, -3.0, 0.2));
  box.setAngularVelocity(Vec3(0.0, 2.0, 0.0));
  world.bodies.push_back(box);
  world.names.push_back("box");
  ImpulseParams params = gatheringParams(ContactGatheringMode::OncePerStep);
  params.predictedAnchor = true;
  ContactGathering cached(params);
  ContactGathering exact(gatheringParams(ContactGatheringMode::EveryPass));
  const std::pair<int, int> pair(0, 1);
  const auto compare = [&](double tolerance) {
    const auto reference = gathered(world, exact, GravityMode::VelocityPlusGravity);
    const auto found = gathered(world, cached, GravityMode::VelocityPlusGravity);
    REQUIRE(reference.count(pair) == 1);
    REQUIRE(found.count(pair) == 1);
    CHECK(std::abs(found.at(pair) - reference.at(pair)) <= tolerance);
  };
  const auto kick = [&](const Vec3& dv, const Vec3& dw) {
    RigidBody& b = world.bodies[1];
    b.setVelocity(b.v + dv);
    b.setAngularVelocity(b.omega + dw);
  };
  compare(1e-12);
  compare(1e-12);
  CHECK(cached.passNarrowPhases() == 0);
  kick(Vec3(0.0, 0.3, 0.0), Vec3(0.3, 0.0, 0.0));
  compare(2e-4);
  CHECK(cached.passNarrowPhases() == 0);
  kick(Vec3(3.0, 0.0, 0.0), Vec3::Zero());
  compare(1e-12);
  CHECK(cached.passNarrowPhases() > 0);
  // Told that the box touches nothing at the step's start (setTouching, as damped integration
  // tells it from the contacts its last step left), the gathering leaves it unanchored: fast,
  // its pair gets the exact narrow phase in every pass, as without the anchor.
  const std::vector<char> touchingNone(world.bodies.size(), 0);
  ContactGathering unanchored(params);
  unanchored.setTouching(&touchingNone);
  for (int pass = 0; pass < 2; ++pass) {
    const auto reference = gathered(world, exact, GravityMode::VelocityPlusGravity);
    const auto found = gathered(world, unanchored, GravityMode::VelocityPlusGravity);
    REQUIRE(found.count(pair) == 1);
    CHECK(found.at(pair) == reference.at(pair));
  }
  CHECK(unanchored.passNarrowPhases() > 0);
}

TEST_CASE("On a settling pile the cache misses contacts of edge-edge pairs, and none when they are gathered exactly or keep their face corners",
          "[impulse_damped][contact_gathering][reference]") {
  // pile343.json a second after its drop (damped integration, e = 0), then the passes of ten
  // steps run by hand, each pass' once-per-step contacts compared with every-pass gathering on
  // the same world: a pair every-pass finds more than 1 mm deep at the pass' poses must be
  // among them. The cache predicts the material points of the feature found at the step's
  // start, and a small relative turn brings another corner of an edge-edge pair into contact,
  // so the default misses some (hundreds here, up to 7 mm deep), and the predicted anchor more;
  // with ImpulseParams::exactEdgePairs those pairs get the exact narrow phase, and with
  // ImpulseParams::edgeCorners they keep the corners of their best face, and none is missed.
  std::string path = BOXSIM_SOURCE_DIR;
  path += "/chapters/impulse_damped/scenes/pile343.json";
  Scene scene = loadScene(path);
  scene.world.restitution = 0.0;
  DampedIntegrationStepper stepper{DampedIntegrationParams{}};
  for (int k = 0; k < 60; ++k) stepper.step(scene.world, kDt);
  const double margin = ImpulseParams{}.contactMargin * 0.5;
  const auto contactsOf = [](const std::vector<ImpulseContact>& contacts) {
    std::map<std::pair<int, int>, double> found;
    for (const ImpulseContact& c : contacts) found[{c.a, c.b}] = c.depth;
    return found;
  };
  // The gatherings compared: the default, exact edge pairs, edge corners, the predicted anchor
  // alone and with edge corners.
  struct Mode {
    const char* name;
    bool exactEdges, corners, anchor;
    long compared = 0, missed = 0;
    double deepest = 0.0;  // m, the deepest contact missed
    long matched = 0;         // contacts both gatherings find
    double depthError = 0.0;  // m, the sum of their |depth - the narrow phase's depth|
    long extra = 0;           // overlapping contacts the narrow phase does not find
    double meanDepthError() const { return depthError / static_cast<double>(matched); }
  };
  std::vector<Mode> modes = {{"default", false, false, false},
                             {"exact edge pairs", true, false, false},
                             {"edge corners", false, true, false},
                             {"predicted anchor", false, false, true},
                             {"predicted anchor with edge corners", false, true, true}};
  for (int k = 0; k < 10; ++k) {
    for (Mode& mode : modes) {
      ImpulseParams params;
      params.exactEdgePairs = mode.exactEdges;
      params.edgeCorners = mode.corners;
      params.predictedAnchor = mode.anchor;
      ContactGathering cached(params);
      World world = scene.world;
      const std::vector<char> stable(world.bodies.size(), 0);
      cached.beginStep(world, kDt, GravityMode::VelocityPlusGravity, margin);
      for (int pass = 0; pass < 15; ++pass) {
        World before = world;
        ContactGathering exact(gatheringParams(ContactGatheringMode::EveryPass));
        const auto reference =
            contactsOf(exact.begin(before, kDt, GravityMode::VelocityPlusGravity, margin));
        exact.end(before);
        // The pass itself, its contacts gathered once per step (collision passes, then
        // contact passes with the restitution ramp, as RESOLVECOLLISIONS and RESOLVECONTACTS).
        World look = world;
        const auto found =
            contactsOf(cached.begin(look, kDt, GravityMode::VelocityPlusGravity, margin));
        cached.end(look);
        // How deep the contacts both find are: the cache's depth against the narrow phase's.
        for (const auto& [pair, depth] : found) {
          const auto exactDepth = reference.find(pair);
          if (exactDepth == reference.end()) {
            mode.extra += depth > 0.0;
            continue;
          }
          ++mode.matched;
          mode.depthError += std::abs(depth - exactDepth->second);
        }
        for (const auto& [pair, depth] : reference)
          if (depth > 1e-3) {
            ++mode.compared;
            if (found.count(pair) == 0) {
              ++mode.missed;
              mode.deepest = std::max(mode.deepest, depth);
            }
          }
        const double restitution = pass < 5 ? 0.0 : -1.0 + (pass - 4) / 10.0;
        impulsePass(world, kDt, restitution, GravityMode::VelocityPlusGravity,
                    pass < 5 ? GravityMode::VelocityNoGravity : GravityMode::VelocityPlusGravity,
                    margin, cached, stable, nullptr, BeforeCollide{}, nullptr,
                    IslandSettling::Never, 0.0);
      }
      cached.endStep();
    }
    stepper.step(scene.world, kDt);
  }
  for (const Mode& mode : modes) {
    INFO(mode.name << ": " << mode.compared << " contacts deeper than 1 mm compared, "
                   << mode.missed << " missed, the deepest " << mode.deepest << " m; "
                   << mode.matched << " found by both, their depths off by "
                   << mode.meanDepthError() << " m on average; " << mode.extra
                   << " overlapping contacts the narrow phase does not find");
    CHECK(mode.compared > 1000);
    // The finding: the cache as it stands misses edge-edge pairs' corners.
    if (!mode.exactEdges && !mode.corners) CHECK(mode.missed > 0);
  }
  // Gathered exactly, none is missed. With the corners kept (predicted like the points, not
  // found), a few are, against the same gathering without them: at most a twentieth as many
  // (measured: 7 of 588, and 18 of 675 under the anchor), none half as deep as its deepest
  // (1.5 mm of 6.8, 1.8 of 9.7), and the depths of the contacts both find are a quarter as far
  // off at most (measured: 8.7 µm on average against 77, 22 against 133 under the anchor).
  CHECK(modes[1].missed == 0);
  for (const auto& [with, without] : {std::pair{2, 0}, std::pair{4, 3}}) {
    INFO(modes[with].name << " against " << modes[without].name);
    CHECK(20 * modes[with].missed <= modes[without].missed);
    CHECK(modes[with].deepest < 0.5 * modes[without].deepest);
    CHECK(modes[with].meanDepthError() < 0.25 * modes[without].meanDepthError());
  }
}
