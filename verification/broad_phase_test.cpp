// Verification of the broad phase (\thesis{§4.1}): sweep and prune against the all-pairs test
// as an independent reference. The claim is equality, element for element and in order, not
// "the same pairs up to order": the narrow phase and everything after it must see the same
// sequence whichever broad phase runs, or trajectories would differ bit for bit.
//
// Scenes are chosen to break a sweep: boxes whose sizes span two decades (long intervals
// overlap many short ones along the sweep axis), boxes snapped to a grid so bounds touch
// exactly and sort keys tie, immovable ground and walls at arbitrary indices, and the
// thesis' pyramid and clump, where every contact is an exact touch.
#include <catch2/catch.hpp>

#include "seeded_random.hpp"
#include "test_worlds.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/collision/contact_manifold.hpp"
#include "boxsim/collision/separating_axis.hpp"
#include "boxsim/collision/sweep_and_prune.hpp"
#include "boxsim/io/scene_builders.hpp"

using namespace boxsim;

namespace {

using Pairs = std::vector<std::pair<int, int>>;


/// A random scene of 2-300 boxes with edges of 0.05-5 m in a cube whose side grows with the
/// cube root of the count, so density (and the share of overlapping pairs) varies from scene
/// to scene but not with size. Every third scene is snapped: axis-aligned boxes with edges and
/// positions on a 0.25 m grid, where many bounds touch exactly and many sort keys tie.
/// With `immovables`, a ground and two walls are inserted at random places in the body list.
World randomScene(testing::SeededRandom& random, bool snapped, bool immovables) {
  World world;
  const int count = random.integer(2, 300);
  double side = random.uniform(1.0, 6.0) * std::cbrt(static_cast<double>(count));
  // A multiple of 0.5 m keeps every snapped coordinate, and so every bound, exact in binary.
  if (snapped) side = 0.5 * std::round(2.0 * side);
  const int groundAt = immovables ? random.integer(0, count) : -1;
  const int wallsAt = immovables ? random.integer(0, count) : -1;
  for (int i = 0; i <= count; ++i) {
    if (i == groundAt) world.addGround(0.0, side);
    if (i == wallsAt) {
      for (double x : {-0.5 * side, 0.5 * side}) {
        RigidBody wall = RigidBody::immovableBox(Vec3(0.1, side, side));
        wall.s.x = Vec3(x, side, 0.0);
        world.add(wall, "wall");
      }
    }
    if (i == count) break;
    Vec3 edges, x;
    for (int k = 0; k < 3; ++k) {
      edges[k] = snapped ? random.snapped(0.25, 5.0, 0.25) : random.uniform(0.05, 5.0);
      x[k] = snapped ? random.snapped(-0.5 * side, 0.5 * side, 0.25)
                     : random.uniform(-0.5 * side, 0.5 * side);
    }
    x.y() += 0.5 * side;  // mostly above the ground, whose top is y = 0
    RigidBody body = RigidBody::box(0.5 * edges, 1.0);
    body.s.x = x;
    if (!snapped) body.s.q = random.rotation();
    world.add(body, "box");
  }
  return world;
}

/// Bitwise equality of two manifolds: both broad phases must hand the narrow phase the same
/// pairs, so its answers must be the same bits, not merely close.
bool sameManifold(const ContactManifold& m, const ContactManifold& n) {
  if (m.a != n.a || m.b != n.b || m.normal != n.normal || m.kind != n.kind ||
      m.depth != n.depth || m.count != n.count)
    return false;
  for (int k = 0; k < m.count; ++k)
    if (m.points[k].position != n.points[k].position || m.points[k].depth != n.points[k].depth ||
        m.points[k].featureId != n.points[k].featureId)
      return false;
  return true;
}

bool sameContacts(const std::vector<ContactManifold>& p, const std::vector<ContactManifold>& q) {
  if (p.size() != q.size()) return false;
  for (std::size_t k = 0; k < p.size(); ++k)
    if (!sameManifold(p[k], q[k])) return false;
  return true;
}

/// A copy of world whose queries run the given broad phase.
World withBroadPhase(World world, BroadPhase kind) {
  world.broadPhase = kind;
  return world;
}

/// The reference for bounds given: every pair i < j, not both immovable, whose bounds pass
/// boundsWithin(margin), by the plain double loop.
Pairs pairsWithin(const World& world, const std::vector<Vec3>& lo, const std::vector<Vec3>& hi,
                  double margin) {
  Pairs pairs;
  const int n = static_cast<int>(world.bodies.size());
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      if (!(world.bodies[i].immovable && world.bodies[j].immovable) &&
          boundsWithin(lo[i], hi[i], lo[j], hi[j], margin))
        pairs.emplace_back(i, j);
  return pairs;
}

/// The clump of \thesis{Fig. 6.7} after every cube has moved for t seconds at its initial
/// velocity: by t = 0.5 s neighbours overlap, and they keep overlapping more after that.
World collapsedClump(int count, double t) {
  World world;
  world.addGround(0.0, 100.0);
  addClump(world, ClumpSpec{count});
  for (RigidBody& body : world.bodies) {
    body.s.x += t * body.v;
    body.updateDerived();
  }
  return world;
}

}  // namespace

TEST_CASE("Sweep and prune returns exactly the all-pairs list on 200 random scenes",
          "[collision][broad_phase]") {
  testing::SeededRandom random(20030501);
  long totalPairs = 0;
  for (int scene = 0; scene < 200; ++scene) {
    const bool snapped = scene % 3 == 0;
    const bool immovables = scene % 2 == 0;
    const World world = randomScene(random, snapped, immovables);
    for (double margin : {0.0, 0.1}) {
      INFO("scene " << scene << ", " << world.bodies.size() << " bodies, margin " << margin
                    << (snapped ? ", snapped" : "") << (immovables ? ", with immovables" : ""));
      const Pairs reference = candidatePairs(withBroadPhase(world, BroadPhase::AllPairs), margin);
      REQUIRE(sweepAndPrunePairs(world, margin) == reference);
      REQUIRE(candidatePairs(withBroadPhase(world, BroadPhase::SweepAndPrune), margin) ==
              reference);
      totalPairs += static_cast<long>(reference.size());
    }
  }
  // The scenes must give the comparison something to compare.
  CHECK(totalPairs > 100000);
}

TEST_CASE("Sweep and prune reports touching bounds: the base-20 pyramid's 590 exact contacts",
          "[collision][broad_phase]") {
  World world;
  world.addGround(0.0, 50.0);
  REQUIRE(addPyramid(world, PyramidSpec{20}) == 210);
  // Unit cubes on a half-integer grid touch exactly: 19 + 18 + ... + 0 = 190 side by side in
  // the rows, 2 under each of the 190 cubes above the bottom row, and 20 on the ground.
  const Pairs reference = candidatePairs(withBroadPhase(world, BroadPhase::AllPairs), 0.0);
  CHECK(reference.size() == 190 + 2 * 190 + 20);
  CHECK(sweepAndPrunePairs(world, 0.0) == reference);
  CHECK(candidatePairs(withBroadPhase(world, BroadPhase::SweepAndPrune), 0.1) ==
        candidatePairs(withBroadPhase(world, BroadPhase::AllPairs), 0.1));
}

TEST_CASE("Sweep and prune returns exactly the all-pairs list on the 1000-cube clump",
          "[collision][broad_phase]") {
  World world;
  REQUIRE(addClump(world, ClumpSpec{1000}) == 1000);
  // At the start the cubes are 1 m apart: no pair at margin 0, and at margin 1 m every cube
  // touches its 26 grid neighbours, 3·900 + 6·810 + 4·729 = 10476 pairs on a 10³ grid.
  CHECK(sweepAndPrunePairs(world, 0.0).empty());
  CHECK(candidatePairs(withBroadPhase(world, BroadPhase::AllPairs), 0.0).empty());
  const Pairs neighbours = candidatePairs(withBroadPhase(world, BroadPhase::AllPairs), 1.0);
  CHECK(neighbours.size() == 10476);
  CHECK(sweepAndPrunePairs(world, 1.0) == neighbours);

  for (double t : {0.5, 1.0, 1.5}) {
    const World collapsed = collapsedClump(1000, t);
    for (double margin : {0.0, 0.1}) {
      INFO("t = " << t << " s, margin " << margin);
      const Pairs reference =
          candidatePairs(withBroadPhase(collapsed, BroadPhase::AllPairs), margin);
      CHECK(!reference.empty());
      CHECK(sweepAndPrunePairs(collapsed, margin) == reference);
    }
  }
}

TEST_CASE("findContacts and firstIntersectingPair give identical results with both broad phases",
          "[collision][broad_phase]") {
  testing::SeededRandom random(1968);
  int scenesWithContacts = 0;
  for (int scene = 0; scene < 40; ++scene) {
    const World world = randomScene(random, scene % 3 == 0, scene % 2 == 0);
    for (double margin : {0.0, 0.1}) {
      INFO("scene " << scene << ", margin " << margin);
      const std::vector<ContactManifold> reference =
          findContacts(withBroadPhase(world, BroadPhase::AllPairs), margin);
      CHECK(sameContacts(findContacts(withBroadPhase(world, BroadPhase::SweepAndPrune), margin),
                         reference));
      scenesWithContacts += reference.empty() ? 0 : 1;
    }
    for (double tolerance : {0.0, 0.01, -0.1}) {
      INFO("scene " << scene << ", tolerance " << tolerance);
      CHECK(firstIntersectingPair(withBroadPhase(world, BroadPhase::SweepAndPrune), tolerance) ==
            firstIntersectingPair(withBroadPhase(world, BroadPhase::AllPairs), tolerance));
    }
  }
  CHECK(scenesWithContacts > 60);

  const World clump = collapsedClump(1000, 1.0);
  const std::vector<ContactManifold> reference =
      findContacts(withBroadPhase(clump, BroadPhase::AllPairs), 0.0);
  CHECK(reference.size() > 1000);
  CHECK(sameContacts(findContacts(withBroadPhase(clump, BroadPhase::SweepAndPrune), 0.0),
                     reference));
  CHECK(firstIntersectingPair(withBroadPhase(clump, BroadPhase::SweepAndPrune), 0.0) ==
        firstIntersectingPair(withBroadPhase(clump, BroadPhase::AllPairs), 0.0));
  // A world's default broad phase is sweep and prune.
  CHECK(clump.broadPhase == BroadPhase::SweepAndPrune);
  CHECK(sameContacts(findContacts(clump), reference));
}

TEST_CASE("The grid finds the bodies wider than its cells: a dense clump with a tenth stretched",
          "[collision][broad_phase]") {
  // The grid's cells are sized for all but the widest bodies (kGridCellQuantile); the others
  // look up every cell they reach. A collapsed 1000-cube clump whose every tenth body's bounds
  // are stretched by up to 1.5 m, as a fast body's swept bounds are, and every 13th body
  // immovable, as sleepers stand in: the same pairs as the all-pairs test.
  testing::SeededRandom random(1203);
  World world = collapsedClump(1000, 1.0);
  const std::size_t n = world.bodies.size();
  for (std::size_t i = 1; i < n; i += 13) world.bodies[i].immovable = true;
  std::vector<Vec3> lo(n), hi(n);
  int stretched = 0;
  for (std::size_t i = 0; i < n; ++i) {
    obbBounds(Obb::of(world.bodies[i]), 0.0, lo[i], hi[i]);
    if (i == 0) continue;  // the ground stays as it is
    if (i % 10 != 3) continue;
    const Vec3 shift = random.vector(-1.5, 1.5);
    lo[i] = lo[i].cwiseMin(lo[i] + shift);
    hi[i] = hi[i].cwiseMax(hi[i] + shift);
    ++stretched;
  }
  CHECK(stretched >= 100);
  for (double margin : {0.0, 0.05}) {
    const Pairs reference = pairsWithin(world, lo, hi, margin);
    INFO("margin " << margin);
    CHECK(reference.size() > 5000);  // dense: every body has neighbours
    CHECK(sweepAndPrunePairs(world, lo, hi, margin) == reference);
  }
}

TEST_CASE("refindContacts after some bodies moved equals findContacts, manifold for manifold",
          "[collision][broad_phase]") {
  testing::SeededRandom random(2024);
  int movedPairs = 0;
  BroadPhaseLists lists;
  for (int scene = 0; scene < 40; ++scene) {
    World world = randomScene(random, scene % 3 == 0, scene % 2 == 0);
    const double margin = scene % 4 == 0 ? 0.0 : 0.05;
    const std::vector<ContactManifold> before = findContacts(world, margin);
    // Nudge a random fifth of the bodies by up to half a metre, as FIXCONTACTCONSTRAINTS
    // moves x alone (some move into contact, some out of it).
    std::vector<char> moved(world.bodies.size(), 0);
    for (std::size_t i = 0; i < world.bodies.size(); ++i) {
      if (world.bodies[i].immovable || random.uniform(0, 1) > 0.2) continue;
      world.bodies[i].s.x += random.vector(-0.5, 0.5);
      moved[i] = 1;
    }
    const std::vector<ContactManifold> reference = findContacts(world, margin);
    INFO("scene " << scene << ", margin " << margin);
    CHECK(sameContacts(refindContacts(world, margin, before, moved), reference));
    // With the broad phase's answer given, and with lists kept from the last scene.
    std::vector<ContactManifold> refound;
    const std::vector<std::pair<int, int>> pairs = candidatePairs(world, margin);
    refindContacts(world, margin, before, moved, nullptr, lists, refound, &pairs);
    CHECK(sameContacts(refound, reference));
    refindContacts(world, margin, before, moved, nullptr, lists, refound);
    CHECK(sameContacts(refound, reference));
    for (const ContactManifold& m : reference) movedPairs += (moved[m.a] || moved[m.b]) ? 1 : 0;
  }
  CHECK(movedPairs > 100);  // the merge was exercised, not only the kept pairs
  World world = randomScene(random, false, true);
  CHECK_THROWS_AS(refindContacts(world, 0.0, {}, std::vector<char>(1, 0)), std::invalid_argument);
}

TEST_CASE("Both broad phases over given bounds equal the all-pairs test on those bounds",
          "[collision][broad_phase]") {
  testing::SeededRandom random(77);
  for (int scene = 0; scene < 60; ++scene) {
    const World world = randomScene(random, scene % 3 == 0, scene % 2 == 0);
    const std::size_t n = world.bodies.size();
    // Bounds stretched along a random direction, as contact gathering stretches a body's
    // bounds along its way in a pass.
    std::vector<Vec3> lo(n), hi(n);
    for (std::size_t i = 0; i < n; ++i) {
      obbBounds(Obb::of(world.bodies[i]), 0.0, lo[i], hi[i]);
      const Vec3 shift = random.vector(-2.0, 2.0);
      lo[i] = lo[i].cwiseMin(lo[i] + shift);
      hi[i] = hi[i].cwiseMax(hi[i] + shift);
    }
    const Pairs reference = pairsWithin(world, lo, hi, 0.01);
    INFO("scene " << scene);
    CHECK(sweepAndPrunePairs(world, lo, hi, 0.01) == reference);
    // The world's choice of broad phase over the same bounds: both kinds, the same list.
    for (BroadPhase kind : {BroadPhase::AllPairs, BroadPhase::SweepAndPrune}) {
      INFO(broadPhaseName(kind));
      CHECK(candidatePairs(withBroadPhase(world, kind), lo, hi, 0.01) == reference);
    }
  }
  const World world = randomScene(random, false, false);
  CHECK_THROWS_AS(sweepAndPrunePairs(world, std::vector<Vec3>(1), std::vector<Vec3>(1), 0.0),
                  std::invalid_argument);
  for (BroadPhase kind : {BroadPhase::AllPairs, BroadPhase::SweepAndPrune})
    CHECK_THROWS_AS(candidatePairs(withBroadPhase(world, kind), std::vector<Vec3>(1),
                                   std::vector<Vec3>(1), 0.0),
                    std::invalid_argument);
}

TEST_CASE("separatingAxisTestWithin is the full test but for pairs its faces prove apart beyond "
          "the margin",
          "[collision][sat]") {
  // Random box pairs near each other, a quarter of them aligned (flush faces, ties), margins up
  // to 5 cm. A pair whose full test is within the margin gets the full test's result bit for
  // bit; any other gets a face of its own apart by at least the margin, no deeper than the full
  // test says, and so the same manifold within the margin: none.
  testing::SeededRandom random(6161);
  int within = 0, shortcut = 0;
  for (int k = 0; k < 20000; ++k) {
    const bool aligned = k % 4 == 0;
    const Mat3 ra = aligned ? Mat3::Identity() : Mat3(random.rotation().toRotationMatrix());
    const Mat3 rb = aligned ? Mat3::Identity() : Mat3(random.rotation().toRotationMatrix());
    const Obb a{random.vector(-1.0, 1.0), ra, random.vector(0.05, 1.0)};
    const Obb b{random.vector(-1.5, 1.5), rb, random.vector(0.05, 1.0)};
    const double margin = random.uniform(0.0, 0.05);
    const SeparatingAxisResult full = separatingAxisTest(a, b);
    const SeparatingAxisResult near = separatingAxisTestWithin(a, b, margin);
    INFO("pair " << k);
    if (full.depth > -margin) {
      ++within;
      REQUIRE(testing::sameResult(near, full));
      continue;
    }
    REQUIRE(near.depth <= -margin);
    REQUIRE(near.depth >= full.depth);
    REQUIRE(!near.intersecting);
    REQUIRE(buildContactManifold(a, b, near, margin).count == 0);
    REQUIRE(buildContactManifold(a, b, full, margin).count == 0);
    if (near.kind != full.kind || !sameBits(near.depth, full.depth)) {
      ++shortcut;
      REQUIRE(near.kind != AxisKind::EdgeEdge);
    }
  }
  CHECK(within > 2000);
  CHECK(shortcut > 1000);
  // No margin to speak of: the full test.
  const Obb unit{Vec3::Zero(), Mat3::Identity(), Vec3::Constant(0.5)};
  const Obb far{Vec3(3.0, 0.2, 0.1), Mat3(Eigen::AngleAxisd(0.4, Vec3::UnitY()).toRotationMatrix()),
                Vec3::Constant(0.5)};
  CHECK(sameBits(separatingAxisTestWithin(unit, far, std::nan("")).depth,
                 separatingAxisTest(unit, far).depth));
  CHECK(sameBits(separatingAxisTestWithin(unit, far, -1.0).depth,
                 separatingAxisTest(unit, far).depth));
}

TEST_CASE("separatedBeyond says 'apart' only when the full separating-axis test does",
          "[collision][sat]") {
  // Random box pairs near each other; the axis tried is the full test's own answer for the
  // pair moved by up to 2 cm along each axis (what contact gathering remembers from its last
  // pass). Whenever the shortcut says the pair is apart beyond the margin, the full test must
  // agree. And it must decide every pair apart by 10 cm more than the margin: the move changes
  // the gap along any axis by at most 2 cm times the square root of 3 (3.5 cm), so along the
  // remembered axis such a pair is still apart by more than the margin plus 3 cm.
  testing::SeededRandom random(4242);
  int apart = 0, decided = 0, shortcut = 0;
  for (int k = 0; k < 20000; ++k) {
    Obb a{random.vector(-1.0, 1.0), Mat3(random.rotation().toRotationMatrix()), random.vector(0.05, 1.0)};
    Obb b{random.vector(-1.5, 1.5), Mat3(random.rotation().toRotationMatrix()), random.vector(0.05, 1.0)};
    const double margin = random.uniform(0.0, 0.05);
    Obb earlier = b;
    earlier.center += random.vector(-0.02, 0.02);
    const SeparatingAxisResult axis = separatingAxisTest(a, earlier);
    const SeparatingAxisResult full = separatingAxisTest(a, b);
    const bool fullApart = buildContactManifold(a, b, full, margin).count == 0;
    const bool said = separatedBeyond(a, b, axis, margin);
    if (said) {
      ++shortcut;
      INFO("pair " << k);
      REQUIRE(full.depth <= -margin);
      REQUIRE(fullApart);
    }
    if (full.depth < -margin - 0.1) {
      ++apart;
      decided += said ? 1 : 0;
    }
  }
  CHECK(apart > 1000);
  CHECK(decided == apart);
  CHECK(shortcut > apart);
}

TEST_CASE("DepthAfterTranslation bounds the separating-axis depth after a translation",
          "[collision][sat]") {
  // Random overlapping box pairs, B moved by a random translation up to 0.3 m: the full test's
  // depth afterwards is never below the bound, whichever axis (face or edge) either test picks;
  // flush and aligned boxes (the nudges of FIXCONTACTCONSTRAINTS) included. And the bound is
  // useful: for a face-on-face overlap of 0.2 m and a move of 1 cm it claims more than 0.17 m.
  testing::SeededRandom random(5151);
  int overlapping = 0;
  for (int k = 0; k < 20000; ++k) {
    const bool aligned = k % 4 == 0;
    const Mat3 ra = aligned ? Mat3::Identity() : Mat3(random.rotation().toRotationMatrix());
    const Mat3 rb = aligned ? Mat3::Identity() : Mat3(random.rotation().toRotationMatrix());
    const Obb a{random.vector(-1.0, 1.0), ra, random.vector(0.05, 1.0)};
    Obb b{random.vector(-1.0, 1.0), rb, random.vector(0.05, 1.0)};
    const SeparatingAxisResult before = separatingAxisTest(a, b);
    const Vec3 t = random.vector(-1.0, 1.0).normalized() * random.uniform(0.0, 0.3);
    const double bound = DepthAfterTranslation(a, b, before).atLeast(t.norm());
    if (!(before.depth > 0.0)) {
      CHECK(bound == -std::numeric_limits<double>::infinity());
      continue;
    }
    ++overlapping;
    b.center += t;
    INFO("pair " << k);
    REQUIRE(separatingAxisTest(a, b).depth >= bound);
    REQUIRE(separatingAxisTest(b, a).depth >= bound);
  }
  CHECK(overlapping > 2000);
  const Obb ground{Vec3::Zero(), Mat3::Identity(), Vec3(5.0, 0.5, 5.0)};
  const Obb box{Vec3(0.0, 0.8, 0.0), Mat3::Identity(), Vec3::Constant(0.5)};
  const SeparatingAxisResult sat = separatingAxisTest(ground, box);
  REQUIRE(sat.depth == Approx(0.2));
  CHECK(DepthAfterTranslation(ground, box, sat).atLeast(0.01) > 0.17);
}

TEST_CASE("Sweep and prune matches all pairs when a body's state is not finite",
          "[collision][broad_phase]") {
  World world = collapsedClump(27, 0.5);
  // A NaN centre has NaN bounds, which overlap nothing.
  world.bodies[5].s.x = Vec3(std::nan(""), 1.0, 1.0);
  // A tilted box of infinite length has bounds (-inf, inf) on every axis and so overlaps every
  // body, the other infinite one included: that pair is found once, outside the sweep.
  for (int i : {9, 12}) {
    world.bodies[i].halfExtents.x() = std::numeric_limits<double>::infinity();
    world.bodies[i].s.q = axisAngleDegrees(Vec3(1.0, 1.0, 1.0), 30.0);
    world.bodies[i].updateDerived();
  }
  for (double margin : {0.0, 0.1}) {
    const Pairs reference = candidatePairs(withBroadPhase(world, BroadPhase::AllPairs), margin);
    CHECK(std::count(reference.begin(), reference.end(), std::make_pair(9, 12)) == 1);
    CHECK(sweepAndPrunePairs(world, margin) == reference);
  }
}

TEST_CASE("Broad phase names round-trip and unknown names are rejected with the valid ones",
          "[collision][broad_phase]") {
  for (BroadPhase kind : {BroadPhase::AllPairs, BroadPhase::SweepAndPrune})
    CHECK(parseBroadPhase(broadPhaseName(kind)) == kind);
  CHECK(broadPhaseName(BroadPhase::AllPairs) == "all_pairs");
  CHECK(broadPhaseName(BroadPhase::SweepAndPrune) == "sweep_and_prune");
  CHECK_THROWS_AS(parseBroadPhase("octree"), std::invalid_argument);
  CHECK_THROWS_WITH(parseBroadPhase("octree"),
                    Catch::Contains("all_pairs") && Catch::Contains("sweep_and_prune"));
}
