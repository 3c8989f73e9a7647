// Verification of SETGEOMETRICALLYSTABLE (thesis §5.4, Alg. A.2): the configurations of
// Figs. 5.3-5.6 with the verdicts the thesis gives them, tilted and side-touching boxes, the
// corner tolerance, independence from body and contact order, and the footnote's hull rule
// agreeing with the corner rule.
#include <catch2/catch.hpp>

#include "seeded_random.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/collision/obb.hpp"
#include "boxsim/geometric_stability/geometric_stability.hpp"
#include "boxsim/io/scene_builders.hpp"

using namespace boxsim;

namespace {

/// m: exactly touching boxes (gap 0 up to rounding) get a manifold, 1 mm apart do not.
constexpr double kMargin = 1e-6;

using Names = std::set<std::string>;

/// Adds a box with orientation q at horizontal position (x, z), lowered until its lowest corner
/// touches the plane y = planeY (m).
void addBoxResting(World& world, const std::string& name, const Vec3& halfExtents, double x,
                   double z, const Quat& q, double planeY = 0.0) {
  const Obb box{Vec3::Zero(), q.toRotationMatrix(), halfExtents};
  double lowest = 0.0;
  for (int k = 0; k < 8; ++k) lowest = std::min(lowest, box.corner(k).y());
  addBox(world, name, halfExtents, Vec3(x, planeY - lowest, z), q);
}

const Vec3 kUnitHalf = Vec3::Constant(0.5);

std::vector<char> flagsOf(const World& world, const GeometricStabilityParams& params = {}) {
  return setGeometricallyStable(world, findContacts(world, kMargin), params);
}

/// The names of the stable bodies.
Names stableNames(const World& world, const GeometricStabilityParams& params = {}) {
  const std::vector<char> flags = flagsOf(world, params);
  Names names;
  for (std::size_t i = 0; i < flags.size(); ++i)
    if (flags[i]) names.insert(world.names[i]);
  return names;
}

// --- the scenes (unit cubes on the ground y = 0 unless said otherwise) ---

/// Fig. 5.3 (addOneCornerOver): only one bottom corner of "upper" lies over "lower".
World fig5_3OneCornerOver() {
  World world;
  world.addGround();
  addOneCornerOver(world);
  return world;
}

/// Fig. 5.4 (addBoxOnWiderBox): a cube anywhere on a wider box that rests on the ground.
World fig5_4OnWiderBox(const Quat& topOrientation = Quat::Identity()) {
  World world;
  world.addGround();
  addBoxOnWiderBox(world, topOrientation);
  return world;
}

/// Fig. 5.4 repeated: a tower of 5 unit cubes, each exactly on the one below.
World tower5() {
  World world;
  world.addGround();
  TowerSpec spec;
  spec.count = 5;
  addTower(world, spec);
  return world;
}

/// Fig. 5.5 (addBridge): a 2 x 1 x 1 box bridging two cubes 0.5 m apart; each cube holds two
/// of its corners. Without the right cube only two corners are held.
World fig5_5Bridge(bool withRightSupport = true) {
  World world;
  world.addGround();
  addBridge(world, withRightSupport);
  return world;
}

/// A cube tilted 10° about z, resting on one edge on the ground.
World tiltedOnEdge() {
  World world;
  world.addGround();
  addBoxResting(world, "tilted", kUnitHalf, 0.0, 0.0, axisAngleDegrees(Vec3::UnitZ(), 10.0));
  return world;
}

/// A cube tilted 10° about (1, 0, 1), resting on one corner on the ground.
World tiltedOnCorner() {
  World world;
  world.addGround();
  addBoxResting(world, "tilted", kUnitHalf, 0.0, 0.0,
                axisAngleDegrees(Vec3(1.0, 0.0, 1.0), 10.0));
  return world;
}

/// Fig. 5.3 with a small cube lying wholly on the top face of the unstable upper cube.
World onUnstableBox() {
  World world = fig5_3OneCornerOver();
  addBox(world, "rider", Vec3::Constant(0.2), Vec3(0.75, 2.2, 0.75));
  return world;
}

/// Two cubes side by side on the ground `gap` (m) apart, and a cube on the left one.
World sideBySide(double gap) {
  World world;
  world.addGround();
  addBox(world, "left", kUnitHalf, Vec3(-0.5 - 0.5 * gap, 0.5, 0.0));
  addBox(world, "right", kUnitHalf, Vec3(0.5 + 0.5 * gap, 0.5, 0.0));
  addBox(world, "on_left", kUnitHalf, Vec3(-0.5 - 0.5 * gap, 1.5, 0.0));
  return world;
}

/// The one-box-deep pyramid of base 4 (addPyramid) with a horizontal gap between neighbours
/// (m), without the named boxes. Names are pyramid_r<row>_<k>, k from -x to +x:
///
///                 [r3_0]
///             [r2_0]  [r2_1]
///         [r1_0]  [r1_1]  [r1_2]
///     [r0_0]  [r0_1]  [r0_2]  [r0_3]
World pyramid4Without(double gap, const Names& removed) {
  World full;
  full.addGround();
  PyramidSpec spec;
  spec.base = 4;
  spec.gap = gap;
  addPyramid(full, spec);
  World world;
  for (std::size_t i = 0; i < full.bodies.size(); ++i)
    if (!removed.count(full.names[i])) world.add(full.bodies[i], full.names[i]);
  world.groundIndex = 0;
  return world;
}

/// 5 cm between row neighbours: no side contacts, every upper box still holds two corners on
/// each of the two boxes under it.
constexpr double kPyramidGap = 0.05;

/// Every scene above, for the tests that run on all of them.
std::vector<std::pair<std::string, std::function<World()>>> allScenes() {
  return {
      {"fig5_3", fig5_3OneCornerOver},
      {"fig5_4", [] { return fig5_4OnWiderBox(); }},
      {"fig5_4 yawed", [] { return fig5_4OnWiderBox(axisAngleDegrees(Vec3::UnitY(), 30.0)); }},
      {"tower", tower5},
      {"fig5_5", [] { return fig5_5Bridge(); }},
      {"fig5_5 one support", [] { return fig5_5Bridge(false); }},
      {"tilted edge", tiltedOnEdge},
      {"tilted corner", tiltedOnCorner},
      {"on unstable", onUnstableBox},
      {"side by side", [] { return sideBySide(0.0); }},
      {"side by side gap", [] { return sideBySide(1e-3); }},
      {"pyramid", [] { return pyramid4Without(kPyramidGap, {}); }},
      {"pyramid touching", [] { return pyramid4Without(0.0, {}); }},
      {"pyramid -2", [] { return pyramid4Without(kPyramidGap, {"pyramid_r0_1", "pyramid_r0_2"}); }},
      {"pyramid -1", [] { return pyramid4Without(kPyramidGap, {"pyramid_r0_1"}); }},
  };
}

/// A fixed permutation of 0..n-1 from GSL's MT19937 with the given seed.
std::vector<int> permutation(int n, unsigned long seed) {
  std::vector<int> order(n);
  for (int i = 0; i < n; ++i) order[i] = i;
  testing::SeededRandom(seed).shuffle(order);
  return order;
}

}  // namespace

TEST_CASE("Fig. 5.3: a box with only one corner over the box below is not stable",
          "[geometric_stability][thesis_claim]") {
  const World world = fig5_3OneCornerOver();
  // The manifold holds the one corner (and three clipped points that are not corners).
  REQUIRE(findContacts(world, kMargin).size() == 2);
  CHECK(stableNames(world) == Names{"ground", "lower"});
}

TEST_CASE("A box whose centre is over its support but two corners overhang is not stable",
          "[geometric_stability][thesis_claim]") {
  // §5.4 asks for all four corners: contact forces of any size on the overhanging half tip it.
  World world;
  world.addGround();
  addBox(world, "lower", kUnitHalf, Vec3(0.0, 0.5, 0.0));
  addBox(world, "upper", kUnitHalf, Vec3(0.3, 1.5, 0.0));
  CHECK(stableNames(world) == Names{"ground", "lower"});
}

TEST_CASE("Fig. 5.4: a box wholly on a larger stable box is stable, at any yaw",
          "[geometric_stability][thesis_claim]") {
  CHECK(stableNames(fig5_4OnWiderBox()) == Names{"ground", "base", "top"});
  // Yawed about y the bottom face stays level and its corners move with the box.
  CHECK(stableNames(fig5_4OnWiderBox(axisAngleDegrees(Vec3::UnitY(), 30.0))) ==
        Names{"ground", "base", "top"});
}

TEST_CASE("Fig. 5.4 chained: every cube of a tower of 5 on the ground is stable",
          "[geometric_stability][thesis_claim]") {
  const World world = tower5();
  const std::vector<char> flags = flagsOf(world);
  REQUIRE(flags.size() == 6);
  for (std::size_t i = 0; i < flags.size(); ++i) {
    INFO(world.names[i]);
    CHECK(flags[i] == 1);
  }
}

TEST_CASE("Fig. 5.5: a box bridging two stable boxes is stable, on one of them it is not",
          "[geometric_stability][thesis_claim]") {
  CHECK(stableNames(fig5_5Bridge(true)) == Names{"ground", "left", "right", "bridge"});
  CHECK(stableNames(fig5_5Bridge(false)) == Names{"ground", "left"});
}

TEST_CASE("A box lying on its side (a face other than its -y face down) is stable",
          "[geometric_stability][invariant]") {
  // Rotated 90° about x, one of the box's z faces is its bottom face: 2 m along x, 0.5 m
  // along z, and the box stands 1 m high.
  World world;
  world.addGround();
  addBoxResting(world, "plank", Vec3(1.0, 0.25, 0.5), 0.0, 0.0,
                axisAngleDegrees(Vec3::UnitX(), 90.0));
  CHECK(stableNames(world) == Names{"ground", "plank"});
}

TEST_CASE("A tilted box resting on an edge or a corner is not stable",
          "[geometric_stability][thesis_claim]") {
  // Its contact normal is the ground's +y, but its own outward normal there is not -y.
  const World edge = tiltedOnEdge();
  REQUIRE(findContacts(edge, kMargin).size() == 1);
  CHECK(stableNames(edge) == Names{"ground"});
  const World corner = tiltedOnCorner();
  REQUIRE(findContacts(corner, kMargin).size() == 1);
  CHECK(stableNames(corner) == Names{"ground"});
}

TEST_CASE("A box tilted beyond the normal tolerance is not stable even with four corners held",
          "[geometric_stability][invariant]") {
  // Tilted 1° about z a cube lifts one edge 17 mm; a 2 cm contact margin still gives all four
  // bottom corners as manifold points, along the ground's +y normal. 1 - cos 1° = 1.5e-4: not
  // level under the default 1e-4, level under 1e-3.
  World world;
  world.addGround();
  addBoxResting(world, "tilted", kUnitHalf, 0.0, 0.0, axisAngleDegrees(Vec3::UnitZ(), 1.0));
  const std::vector<ContactManifold> contacts = findContacts(world, 0.02);
  REQUIRE(contacts.size() == 1);
  REQUIRE(contacts.front().count == 4);
  CHECK(setGeometricallyStable(world, contacts) == std::vector<char>{1, 0});
  GeometricStabilityParams loose;
  loose.normalTolerance = 1e-3;
  CHECK(setGeometricallyStable(world, contacts, loose) == std::vector<char>{1, 1});
}

TEST_CASE("A box wholly on a box that is not stable is not stable",
          "[geometric_stability][thesis_claim]") {
  CHECK(stableNames(onUnstableBox()) == Names{"ground", "lower"});
}

TEST_CASE("A side contact rules out both boxes and everything resting on them",
          "[geometric_stability][thesis_claim]") {
  // §5.4: every contact normal must be along ±y. Touching side by side, the two cubes push
  // each other horizontally, so neither is stable and neither is the cube on the left one.
  CHECK(stableNames(sideBySide(0.0)) == Names{"ground"});
  // 1 mm apart they do not touch: all three are stable.
  CHECK(stableNames(sideBySide(1e-3)) == Names{"ground", "left", "right", "on_left"});
}

TEST_CASE("The ground and other immovable bodies are stable whatever touches them",
          "[geometric_stability][invariant]") {
  World alone;
  alone.addGround();
  addBox(alone, "falling", kUnitHalf, Vec3(0.0, 3.0, 0.0));  // no contact at all
  CHECK(stableNames(alone) == Names{"ground"});
  CHECK(stableNames(tiltedOnCorner()) == Names{"ground"});
  // An immovable slab resting on a box that is not stable keeps its flag.
  World slab = tiltedOnEdge();
  const double top = slab.bodies[1].s.x.y() + 0.5 * (std::cos(kPi / 18.0) + std::sin(kPi / 18.0));
  RigidBody wall = RigidBody::immovableBox(Vec3(2.0, 0.1, 2.0));
  wall.s.x = Vec3(0.0, top + 0.1, 0.0);
  slab.add(wall, "slab");
  REQUIRE(findContacts(slab, kMargin).size() == 2);
  CHECK(stableNames(slab) == Names{"ground", "slab"});
}

TEST_CASE("Fig. 5.6: the base-4 pyramid without its bottom-centre boxes is stable only where "
          "its support is intact",
          "[geometric_stability][thesis_claim]") {
  // With a gap between row neighbours every box of the whole pyramid holds its four corners
  // on stable boxes (row r box k spans the inner halves of row r-1 boxes k and k+1).
  const Names full = stableNames(pyramid4Without(kPyramidGap, {}));
  CHECK(full.size() == 11);

  // Without r0_1 and r0_2 (the two centre boxes of the even base): r0_0 and r0_3 still stand
  // on the ground. r1_0 holds two corners on r0_0, its other two are over the gap; r1_1 has
  // nothing under it; r1_2 mirrors r1_0. Rows 2 and 3 stand on unstable boxes.
  CHECK(stableNames(pyramid4Without(kPyramidGap, {"pyramid_r0_1", "pyramid_r0_2"})) ==
        Names{"ground", "pyramid_r0_0", "pyramid_r0_3"});

  // Without r0_1 only: r0_0, r0_2, r0_3 stand on the ground. r1_0 (on r0_0 and the gap) and
  // r1_1 (on the gap and r0_2) lose two corners; r1_2 stands on r0_2 and r0_3, both stable.
  // r2_0 stands on r1_0 and r1_1, r2_1 on r1_1 (unstable) and r1_2: neither; nor r3_0.
  CHECK(stableNames(pyramid4Without(kPyramidGap, {"pyramid_r0_1"})) ==
        Names{"ground", "pyramid_r0_0", "pyramid_r0_2", "pyramid_r0_3", "pyramid_r1_2"});
}

TEST_CASE("A pyramid whose row neighbours touch has no stable box: side contacts rule them out",
          "[geometric_stability][thesis_claim]") {
  // PyramidSpec's default gap is 0: each bottom box touches a neighbour, so the rule of §5.4
  // rejects it, and with it everything above. Fig. 5.6's dark boxes need gaps between them.
  CHECK(stableNames(pyramid4Without(0.0, {})) == Names{"ground"});
}

TEST_CASE("A corner counts as held within the corner tolerance and not beyond it",
          "[geometric_stability][invariant]") {
  // Tolerance 1e-3 of the 0.5 m half extent: 0.5 mm. An upper cube overhanging its lower cube
  // by 0.1 mm is flush; by 2 mm it overhangs.
  const auto overhang = [](double dx) {
    World world;
    world.addGround();
    addBox(world, "lower", kUnitHalf, Vec3(0.0, 0.5, 0.0));
    addBox(world, "upper", kUnitHalf, Vec3(dx, 1.5, 0.0));
    return stableNames(world);
  };
  CHECK(overhang(1e-4) == Names{"ground", "lower", "upper"});
  CHECK(overhang(2e-3) == Names{"ground", "lower"});
  GeometricStabilityParams loose;
  loose.cornerTolerance = 1e-2;  // 5 mm
  World world;
  world.addGround();
  addBox(world, "lower", kUnitHalf, Vec3(0.0, 0.5, 0.0));
  addBox(world, "upper", kUnitHalf, Vec3(2e-3, 1.5, 0.0));
  CHECK(stableNames(world, loose) == Names{"ground", "lower", "upper"});
}

TEST_CASE("The verdict does not depend on the order of bodies or of contacts",
          "[geometric_stability][determinism]") {
  for (const auto& [name, build] : allScenes()) {
    INFO(name);
    const World world = build();
    const std::vector<char> flags = flagsOf(world);

    // Bodies shuffled (fixed seed), then the flags mapped back to the original indices.
    const int n = static_cast<int>(world.bodies.size());
    const std::vector<int> order = permutation(n, 20030501ul);
    World shuffled;
    for (int j = 0; j < n; ++j) shuffled.add(world.bodies[order[j]], world.names[order[j]]);
    const std::vector<char> shuffledFlags = flagsOf(shuffled);
    std::vector<char> back(n, 0);
    for (int j = 0; j < n; ++j) back[order[j]] = shuffledFlags[j];
    CHECK(back == flags);

    // Contacts reversed.
    std::vector<ContactManifold> contacts = findContacts(world, kMargin);
    std::reverse(contacts.begin(), contacts.end());
    CHECK(setGeometricallyStable(world, contacts) == flags);
  }
}

TEST_CASE("The footnote's support-hull rule agrees with the corner rule on every scene",
          "[geometric_stability][reference]") {
  // For boxes the two are the same test (see GeometricStabilityParams::useSupportHull): an
  // independent implementation of the verdict by convex hulls.
  GeometricStabilityParams hull;
  hull.useSupportHull = true;
  for (const auto& [name, build] : allScenes()) {
    INFO(name);
    const World world = build();
    CHECK(flagsOf(world, hull) == flagsOf(world));
  }
}

TEST_CASE("On yawed bridges the verdict matches a direct test of the corners against the "
          "support faces",
          "[geometric_stability][reference]") {
  // Brute force: a 2.4 x 1 x 0.8 box yawed about y on two cubes stretched along z, over a grid
  // of yaw angles, support spacings and support depths. The reference asks, for each bottom
  // corner, whether it lies inside the top face of one of the supports (xz). Configurations
  // with a corner within twice the corner tolerance of a support's edge are left out: there
  // the two tests may rightly differ.
  const Vec3 bridgeHalf(1.2, 0.5, 0.4);
  const double tol = GeometricStabilityParams{}.cornerTolerance * 0.4;  // m
  int stableCases = 0;
  int unstableCases = 0;
  for (int yawStep = 0; yawStep < 18; ++yawStep)
    for (int sepStep = 0; sepStep < 8; ++sepStep)
      for (int depthStep = 0; depthStep < 7; ++depthStep) {
        const double yaw = 5.0 * yawStep;
        const double sep = 0.55 + 0.1 * sepStep;
        const Vec3 supportHalf(0.5, 0.5, 0.3 + 0.15 * depthStep);
        World world;
        world.addGround();
        addBox(world, "left", supportHalf, Vec3(-sep, 0.5, 0.0));
        addBox(world, "right", supportHalf, Vec3(sep, 0.5, 0.1));
        addBox(world, "bridge", bridgeHalf, Vec3(0.0, 1.5, 0.0),
               axisAngleDegrees(Vec3::UnitY(), yaw));

        const Obb bridge = Obb::of(world.bodies[3]);
        bool allInside = true;
        bool clear = true;
        for (int k = 0; k < 8; ++k) {
          if ((k >> 1) & 1) continue;  // bit 1 set: a top corner (Obb::corner)
          const Vec3 c = bridge.corner(k);
          double inside = -1e9;  // m: how far inside the best support face (negative: outside)
          for (int s = 1; s <= 2; ++s) {
            const Vec3 d = c - world.bodies[s].s.x;
            inside = std::max(inside, std::min(supportHalf.x() - std::abs(d.x()),
                                               supportHalf.z() - std::abs(d.z())));
          }
          allInside = allInside && inside > 0.0;
          clear = clear && std::abs(inside) > 2.0 * tol;
        }
        if (!clear) continue;
        (allInside ? stableCases : unstableCases) += 1;
        INFO("yaw " << yaw << "° spacing " << sep << " m support depth " << supportHalf.z());
        CHECK((flagsOf(world)[3] == 1) == allInside);
      }
  // The grid holds both verdicts in number, so the comparison means something.
  CHECK(stableCases > 50);
  CHECK(unstableCases > 50);
}

TEST_CASE("Invalid input is reported", "[geometric_stability][errors]") {
  const World world = tower5();
  std::vector<ContactManifold> contacts = findContacts(world, kMargin);
  contacts.front().b = 99;
  CHECK_THROWS_AS(setGeometricallyStable(world, contacts), std::invalid_argument);
  GeometricStabilityParams bad;
  bad.normalTolerance = 1.0;
  CHECK_THROWS_AS(setGeometricallyStable(world, {}, bad), std::invalid_argument);
  bad = GeometricStabilityParams{};
  bad.cornerTolerance = -1.0;
  CHECK_THROWS_AS(setGeometricallyStable(world, {}, bad), std::invalid_argument);
}
