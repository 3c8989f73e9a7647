// Verification of the collision module (\thesis{§3.2}): Eberly's separating-axis test, the
// contact manifold and the broad phase, against closed-form contacts, brute-force corner
// projections, and the symmetries every answer must have (swapping the boxes, moving both
// rigidly).
//
// Tolerances. Unit-sized boxes put every intermediate value near 1 m, where one rounding is
// ~1.1e-16 m; a few dozen operations stay far below 1e-12, which is the tolerance of every
// closed-form check unless stated. Edge-edge depths carry Eberly's epsilon on purpose:
// SeparatingAxisParams::absCEpsilon (1e-12) times the four half extents over |a_i x b_j|.
#include <catch2/catch.hpp>

#include "seeded_random.hpp"
#include "test_worlds.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/collision/contact_manifold.hpp"
#include "boxsim/collision/kept_narrow_phase.hpp"
#include "boxsim/collision/separating_axis.hpp"
#include "boxsim/core/math.hpp"
#include "boxsim/impulse_damped/parallel_for.hpp"

using namespace boxsim;

namespace {

constexpr double kRound = 1e-12;  // closed-form tolerance for unit boxes (see file comment)

Mat3 rotation(double angle, const Vec3& axis) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

Obb cube(const Vec3& center, const Mat3& axes = Mat3::Identity(), double half = 0.5) {
  return Obb{center, axes, Vec3::Constant(half)};
}


std::vector<Vec3> positions(const ContactManifold& m) {
  std::vector<Vec3> p;
  for (int k = 0; k < m.count; ++k) p.push_back(m.points[k].position);
  return p;
}

/// Same size and every point of each set within tol of some point of the other.
bool samePointSet(const std::vector<Vec3>& p, const std::vector<Vec3>& q, double tol) {
  if (p.size() != q.size()) return false;
  auto covered = [tol](const std::vector<Vec3>& from, const std::vector<Vec3>& to) {
    for (const Vec3& x : from) {
      bool found = false;
      for (const Vec3& y : to) found = found || (x - y).norm() <= tol;
      if (!found) return false;
    }
    return true;
  };
  return covered(p, q) && covered(q, p);
}

/// Depth of A and B along unit axis n from their corners: an independent reference for the
/// projection radii that Eberly writes through C = A^T B.
double bruteDepth(const Obb& a, const Obb& b, const Vec3& n) {
  double aLo = 1e300, aHi = -1e300, bLo = 1e300, bHi = -1e300;
  for (int k = 0; k < 8; ++k) {
    aLo = std::min(aLo, n.dot(a.corner(k)));
    aHi = std::max(aHi, n.dot(a.corner(k)));
    bLo = std::min(bLo, n.dot(b.corner(k)));
    bHi = std::max(bHi, n.dot(b.corner(k)));
  }
  return std::min(aHi - bLo, bHi - aLo);
}

Obb moved(const Obb& box, const Mat3& Q, const Vec3& t) {
  return Obb{Vec3(Q * box.center + t), Mat3(Q * box.axes), box.halfExtents};
}

/// Area of the convex quadrilateral through 4 points (any order) seen along n.
double quadArea(std::vector<Vec3> p, const Vec3& n) {
  // Order by angle about the centroid in the plane, then the shoelace formula.
  const Vec3 c = (p[0] + p[1] + p[2] + p[3]) / 4.0;
  const Vec3 e1 = (p[0] - c).normalized();
  const Vec3 e2 = n.cross(e1);
  std::sort(p.begin(), p.end(), [&](const Vec3& x, const Vec3& y) {
    return std::atan2(e2.dot(x - c), e1.dot(x - c)) < std::atan2(e2.dot(y - c), e1.dot(y - c));
  });
  double area = 0.0;
  for (int k = 0; k < 4; ++k) area += 0.5 * (p[k] - c).cross(p[(k + 1) % 4] - c).dot(n);
  return area;
}

/// The standard configurations, all overlapping, none with exactly tied points.
struct Config {
  const char* name;
  Obb a, b;
};

std::vector<Config> configurations() {
  std::vector<Config> c;
  c.push_back({"flush faces", Obb{Vec3::Zero(), Mat3::Identity(), Vec3(1.0, 0.5, 1.0)},
               Obb{Vec3(0.1, 0.69, -0.2), Mat3::Identity(), Vec3(0.3, 0.2, 0.4)}});
  const Mat3 corner = rotation(kPi / 4, Vec3::UnitZ()) * rotation(kPi / 4, Vec3::UnitX());
  c.push_back({"corner down", Obb{Vec3(0, -0.5, 0), Mat3::Identity(), Vec3(2.0, 0.5, 2.0)},
               cube(Vec3(0.2, 0.8, 0.1), corner)});
  c.push_back({"crossed edges", cube(Vec3::Zero(), rotation(kPi / 4, Vec3::UnitZ())),
               cube(Vec3(0.1, std::sqrt(2.0) - 0.01, -0.05), rotation(kPi / 4, Vec3::UnitX()))});
  c.push_back({"tilted on a slab", Obb{Vec3::Zero(), Mat3::Identity(), Vec3(1.0, 0.3, 1.0)},
               cube(Vec3(0.05, 0.75, 0.0), rotation(0.3, Vec3(1, 0, 2)))});
  return c;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Separating-axis test
// ---------------------------------------------------------------------------------------------

TEST_CASE("Boxes 1e-6 m apart are not intersecting and report depth -1e-6", "[collision][sat]") {
  const Obb a = cube(Vec3::Zero());
  const Obb b = cube(Vec3(0.2, 1.0 + 1e-6, -0.1));
  const SeparatingAxisResult sat = separatingAxisTest(a, b);
  CHECK_FALSE(sat.intersecting);
  // 1.0 + 1e-6 is rounded once (1.1e-16); the subtraction from 1.0 is then exact.
  CHECK(sat.depth == Approx(-1e-6).margin(kRound));
  CHECK((sat.normal - Vec3::UnitY()).norm() < kRound);
  CHECK(collideBoxes(a, b).count == 0);
  // A margin larger than the gap gives the nearly-touching boxes their 4-point manifold.
  const ContactManifold near = collideBoxes(a, b, 1e-5);
  CHECK(near.count == 4);
  CHECK(near.depth == Approx(-1e-6).margin(kRound));

  // The same gap between two boxes in a general orientation.
  const Mat3 R = rotation(0.7, Vec3(1, 2, 3));
  const SeparatingAxisResult tilted =
      separatingAxisTest(cube(Vec3::Zero(), R), cube(Vec3(R * Vec3(0, 1.0 + 1e-6, 0)), R));
  CHECK_FALSE(tilted.intersecting);
  CHECK(tilted.depth == Approx(-1e-6).margin(kRound));
}

TEST_CASE("Exactly touching faces are not intersecting and have depth zero", "[collision][sat]") {
  const SeparatingAxisResult sat =
      separatingAxisTest(cube(Vec3::Zero()), cube(Vec3(0.3, 1.0, 0.2)));
  CHECK_FALSE(sat.intersecting);
  CHECK(sat.depth == 0.0);  // every operand is exact: 0.5 + 0.5 - 1.0
  CHECK(collideBoxes(cube(Vec3::Zero()), cube(Vec3(0.3, 1.0, 0.2))).count == 0);

  // Rotated, the touching depth is 0 up to rounding, and "intersecting" still means depth > 0.
  const Mat3 R = rotation(1.1, Vec3(-2, 1, 0.5));
  const SeparatingAxisResult tilted =
      separatingAxisTest(cube(Vec3::Zero(), R), cube(Vec3(R * Vec3(0.3, 0, 1.0)), R));
  CHECK(std::abs(tilted.depth) < kRound);
  CHECK(tilted.intersecting == (tilted.depth > 0.0));
}

TEST_CASE("Flush boxes just apart or touching, in any orientation, pick a face axis over edges",
          "[collision][sat][robustness]") {
  // Two of the edge axes of flush boxes coincide with the face normal, so their gaps equal the
  // face gap up to rounding; without Eberly's epsilon about a third of these cases pick an edge
  // axis, and the nearly-touching manifold collapses to one point.
  testing::SeededRandom random(31);
  for (int trial = 0; trial < 300; ++trial) {
    const Mat3 R = random.rotation().toRotationMatrix();
    for (double gap : {1e-6, 0.0}) {
      INFO("trial " << trial << " gap " << gap);
      const Obb a = cube(Vec3::Zero(), R);
      const Obb b = cube(Vec3(R * Vec3(0.2, 1.0 + gap, 0.1)), R);
      const ContactManifold m = collideBoxes(a, b, 1e-5);
      CHECK(m.kind != AxisKind::EdgeEdge);
      CHECK(m.count == 4);
    }
  }
}

TEST_CASE("Flush faces overlapping or apart by rounding, turned by rounding, give face contacts",
          "[collision][sat][robustness]") {
  // A resting stack's faces overlap or part by rounding and its boxes turn by rounding. An
  // edge axis then ties the face axis to within 1e-11 m, and without the face tie width in
  // the face-or-edge choice rounding handed some pairs a one-point edge contact: a box on two
  // boxes lost its support (the analytic method's gapped pyramid of base 10, after 3 s).
  auto box = [](const Vec3& x, const Quat& q) {
    return Obb{x, q.normalized().toRotationMatrix(), Vec3::Constant(0.5)};
  };
  // That pair, as recorded: A a bottom-row cube, B the cube on it, offset by half a pitch.
  const ContactManifold recorded = collideBoxes(
      box(Vec3(-4.7249999999991301, 0.50000000000015132, -5.9882459721322558e-13),
          Quat(1, 1.9638677046268655e-14, 4.4319124580077291e-13, 4.983036274617227e-14)),
      box(Vec3(-4.2000000000025359, 1.4999999999997446, 5.1467750099473746e-14),
          Quat(1, 3.5841169371348198e-13, 9.4775092176942128e-13, 3.1260873746960258e-12)),
      1e-3);
  CHECK(recorded.kind != AxisKind::EdgeEdge);
  CHECK(recorded.count == 4);
  // And around it: rounding-level turns (up to 1e-11 rad) and overlaps or gaps (±1e-11 m).
  testing::SeededRandom random(47);
  int edge = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Vec3 turnA = random.vector(-5e-12, 5e-12), turnB = random.vector(-5e-12, 5e-12);
    const double gap = random.uniform(-1e-11, 1e-11);
    const ContactManifold m =
        collideBoxes(box(Vec3(0.0, 0.5, 0.0), Quat(1, turnA.x(), turnA.y(), turnA.z())),
                     box(Vec3(0.525, 1.5 + gap, 0.0), Quat(1, turnB.x(), turnB.y(), turnB.z())),
                     1e-3);
    edge += m.kind == AxisKind::EdgeEdge || m.count != 4;
  }
  CHECK(edge == 0);
}

TEST_CASE("The 15-axis depth agrees with brute-force corner projections on 1000 random pairs",
          "[collision][sat][reference]") {
  testing::SeededRandom random(20030501);
  const SeparatingAxisParams params;
  int intersecting = 0, separated = 0;
  for (int trial = 0; trial < 1000; ++trial) {
    const Obb a{random.vector(-1, 1), random.rotation().toRotationMatrix(), random.vector(0.1, 1.0)};
    const Obb b{random.vector(-1, 1), random.rotation().toRotationMatrix(), random.vector(0.1, 1.0)};
    // Least depth over the same 15 axes, from corners; and the smallest |a_i x b_j| tested,
    // which bounds the epsilon's inflation of an edge depth.
    double least = 1e300, minCross = 1.0;
    for (int i = 0; i < 3; ++i) {
      least = std::min(least, bruteDepth(a, b, a.axes.col(i)));
      least = std::min(least, bruteDepth(a, b, b.axes.col(i)));
      for (int j = 0; j < 3; ++j) {
        const Vec3 L = a.axes.col(i).cross(b.axes.col(j));
        if (L.norm() < params.parallelCutoff) continue;
        minCross = std::min(minCross, L.norm());
        least = std::min(least, bruteDepth(a, b, L.normalized()));
      }
    }
    const double tol =
        1e-12 + params.absCEpsilon * 2.0 * (a.halfExtents.sum() + b.halfExtents.sum()) / minCross;
    const SeparatingAxisResult sat = separatingAxisTest(a, b, params);
    INFO("trial " << trial << " sat " << sat.depth << " brute " << least);
    // The reported depth is the corner-projected depth along the reported normal ...
    CHECK(sat.depth == Approx(bruteDepth(a, b, sat.normal)).margin(tol));
    CHECK(sat.normal.dot(b.center - a.center) >= 0.0);
    if (std::abs(least) < tol) continue;  // touching within rounding: either answer is right
    CHECK(sat.intersecting == (least > 0.0));
    if (least > 0.0) {
      // ... the least depth, unless a face axis was preferred within the edge bias ...
      CHECK(sat.depth >= least - tol);
      CHECK(sat.depth <= least / (1.0 - params.edgeBias) + tol);
      ++intersecting;
    } else {
      // ... and, separated, exactly minus the largest gap.
      CHECK(sat.depth == Approx(least).margin(tol));
      ++separated;
    }
  }
  // Both branches must have been exercised for the test to mean anything.
  CHECK(intersecting > 100);
  CHECK(separated > 100);
}

TEST_CASE("The best face axis is the least corner-projected depth over the six face axes, and the "
          "full test's answer whenever that is a face",
          "[collision][sat][reference]") {
  testing::SeededRandom random(20261129);
  int edges = 0;
  for (int trial = 0; trial < 1000; ++trial) {
    const Obb a{random.vector(-1, 1), random.rotation().toRotationMatrix(), random.vector(0.1, 1.0)};
    const Obb b{random.vector(-1, 1), random.rotation().toRotationMatrix(), random.vector(0.1, 1.0)};
    double least = 1e300;
    for (int i = 0; i < 3; ++i)
      least = std::min({least, bruteDepth(a, b, a.axes.col(i)), bruteDepth(a, b, b.axes.col(i))});
    const SeparatingAxisResult face = bestFaceAxis(a, b);
    const SeparatingAxisResult sat = separatingAxisTest(a, b);
    INFO("trial " << trial << " face " << face.depth << " brute " << least);
    CHECK(face.kind != AxisKind::EdgeEdge);
    CHECK(face.normal.dot(b.center - a.center) >= 0.0);
    CHECK(face.depth == Approx(bruteDepth(a, b, face.normal)).margin(1e-12));
    // Near ties go to the larger face, within the tie width (1e-9 of the boxes' size).
    CHECK(face.depth == Approx(least).margin(1e-9 * 4.0));
    CHECK(face.intersecting == (face.depth > 0.0));
    if (sat.kind == AxisKind::EdgeEdge) {
      ++edges;
      continue;
    }
    CHECK(sameBits(face.depth, sat.depth));
    CHECK(sameBits(face.normal, sat.normal));
    CHECK(face.kind == sat.kind);
    CHECK(face.indexA == sat.indexA);
    CHECK(face.indexB == sat.indexB);
  }
  CHECK(edges > 50);  // pairs whose test chose an edge axis, where the face is the test's alone
}

TEST_CASE("Leaving out the edge axes that lose to the face changes no bit of the answer",
          "[collision][sat]") {
  // SeparatingAxisParams::skipLosingEdgeAxes leaves most edge axes out, many of them from the
  // face axes' numbers before their cross product is formed (a bound with a slack of 1e-9 |D|,
  // covering rounding and axes orthonormal within 3e-10). Against the plain loop over all 15
  // axes, every field must agree bit for bit, on pairs where the bound sits close to the bars:
  // boxes resting flush, turned by up to 5 degrees, the one above the other by less than the
  // tie width, far from the origin, on wide grounds, and with nearly parallel edges.
  testing::SeededRandom random(20261127);
  SeparatingAxisParams plain;
  plain.skipLosingEdgeAxes = false;
  const auto small = [&](double angle) {
    return Mat3(Eigen::AngleAxisd(random.uniform(-angle, angle), random.vector(-1, 1).normalized())
                    .toRotationMatrix());
  };
  int faces = 0, edges = 0, apart = 0;
  for (int trial = 0; trial < 6000; ++trial) {
    Obb a, b;
    const int kind = trial % 6;
    if (kind == 0) {  // anything
      a = Obb{random.vector(-1, 1), random.rotation().toRotationMatrix(), random.vector(0.1, 1.0)};
      b = Obb{random.vector(-1, 1), random.rotation().toRotationMatrix(), random.vector(0.1, 1.0)};
    } else if (kind <= 3) {  // resting flush, a little turned, near and far from the origin
      const Vec3 far = kind == 3 ? random.vector(-1e4, 1e4) : Vec3::Zero();
      // Upright on the world axes, or the pair turned as a whole into any orientation.
      const Mat3 base =
          kind == 1 ? Mat3(Mat3::Identity()) : Mat3(random.rotation().toRotationMatrix());
      a = Obb{far, base * small(kind == 1 ? 1e-9 : 0.09), Vec3(0.5, 0.5, 0.5)};
      const double gap = random.uniform(-2e-3, 2e-3) * (trial % 12 < 6 ? 1.0 : 1e-7);
      const Vec3 offset(random.uniform(-0.6, 0.6), 1.0 + gap, random.uniform(-0.6, 0.6));
      b = Obb{Vec3(far + base * offset), base * small(kind == 1 ? 1e-9 : 0.09), Vec3(0.5, 0.5, 0.5)};
    } else if (kind == 4) {  // a box on a wide ground, far from its centre
      a = Obb{Vec3(0, -0.5, 0), Mat3::Identity(), Vec3(150, 0.5, 150)};
      b = Obb{Vec3(random.uniform(-149, 149), 0.5 + random.uniform(-1e-3, 1e-3),
                   random.uniform(-149, 149)),
              small(0.05), random.vector(0.2, 1.0)};
    } else {  // nearly parallel edges: one box turned from the other by 1e-8 to 1e-3 rad
      const Mat3 axes = random.rotation().toRotationMatrix();
      a = Obb{random.vector(-1, 1), axes, random.vector(0.1, 1.0)};
      b = Obb{Vec3(a.center + random.vector(-1.5, 1.5)),
              Mat3(small(std::pow(10.0, random.uniform(-8, -3))) * axes), random.vector(0.1, 1.0)};
    }
    const SeparatingAxisResult fast = separatingAxisTest(a, b);
    const SeparatingAxisResult all = separatingAxisTest(a, b, plain);
    INFO("trial " << trial << " kind " << kind << " depth " << all.depth);
    REQUIRE(testing::sameResult(fast, all));
    if (!all.intersecting) ++apart;
    else if (all.kind == AxisKind::EdgeEdge) ++edges;
    else ++faces;
  }
  // Every kind of answer was compared, resting face contacts most of all.
  CHECK(faces > 2000);
  CHECK(edges > 50);
  CHECK(apart > 500);
}

// ---------------------------------------------------------------------------------------------
// Contact manifolds with closed-form answers
// ---------------------------------------------------------------------------------------------

TEST_CASE("Flush faces overlapping by 1 cm give a 4-point face contact 1 cm deep",
          "[collision][manifold]") {
  const Config c = configurations()[0];
  const ContactManifold m = collideBoxes(c.a, c.b);
  // Both face axes tie at 1 cm; the larger face (A's top) is the reference.
  CHECK(m.kind == AxisKind::FaceA);
  CHECK((m.normal - Vec3::UnitY()).norm() < kRound);
  CHECK(m.depth == Approx(0.01).margin(kRound));
  REQUIRE(m.count == 4);
  // The contact points are B's bottom corners moved up by half the depth, midway between faces.
  std::vector<Vec3> expected;
  for (int k : {0, 1, 4, 5}) expected.push_back(c.b.corner(k) + Vec3(0, 0.005, 0));
  CHECK(samePointSet(positions(m), expected, kRound));
  for (int k = 0; k < 4; ++k) CHECK(m.points[k].depth == Approx(0.01).margin(kRound));
}

TEST_CASE("A box turned 45 degrees about y on another gets a face contact inside both footprints",
          "[collision][manifold]") {
  const Obb a = cube(Vec3::Zero());
  const Mat3 Ry = rotation(kPi / 4, Vec3::UnitY());
  const Obb b = cube(Vec3(0, 0.99, 0), Ry);
  const ContactManifold m = collideBoxes(a, b);
  CHECK(m.kind != AxisKind::EdgeEdge);
  CHECK((m.normal - Vec3::UnitY()).norm() < kRound);
  CHECK(m.depth == Approx(0.01).margin(kRound));
  REQUIRE(m.count == 4);  // the octagon's 8 corners reduced to 4
  for (int k = 0; k < m.count; ++k) {
    const Vec3 p = m.points[k].position;
    const Vec3 inB = Ry.transpose() * (p - b.center);
    INFO("point " << p.transpose());
    CHECK(std::abs(p.x()) <= 0.5 + kRound);
    CHECK(std::abs(p.z()) <= 0.5 + kRound);
    CHECK(std::abs(inB.x()) <= 0.5 + kRound);
    CHECK(std::abs(inB.z()) <= 0.5 + kRound);
    CHECK(p.y() == Approx(0.495).margin(kRound));
  }
}

TEST_CASE("A box standing on a corner touches at one point, its lowest corner",
          "[collision][manifold]") {
  const Config c = configurations()[1];
  int lowest = 0;
  for (int k = 1; k < 8; ++k)
    if (c.b.corner(k).y() < c.b.corner(lowest).y()) lowest = k;
  // The configuration must really have a single corner down: the next one is well above.
  for (int k = 0; k < 8; ++k)
    if (k != lowest) REQUIRE(c.b.corner(k).y() > c.b.corner(lowest).y() + 0.1);
  const double depth = -c.b.corner(lowest).y();
  REQUIRE(depth > 0.0);

  const ContactManifold m = collideBoxes(c.a, c.b);
  CHECK(m.kind == AxisKind::FaceA);
  CHECK((m.normal - Vec3::UnitY()).norm() < kRound);
  REQUIRE(m.count == 1);
  CHECK(m.depth == Approx(depth).margin(kRound));
  CHECK((m.points[0].position - (c.b.corner(lowest) + Vec3(0, depth / 2, 0))).norm() < kRound);
}

TEST_CASE("Crossed edges give an edge-edge contact with the analytic depth, normal and point",
          "[collision][manifold]") {
  // A's top edge runs along z at y = sqrt(2)/2; B's bottom edge runs along x at
  // y = sqrt(2)/2 - 0.01 and z = -0.05. They cross 1 cm deep at (0, sqrt(2)/2, -0.05).
  const Config c = configurations()[2];
  const SeparatingAxisResult sat = separatingAxisTest(c.a, c.b);
  CHECK(sat.kind == AxisKind::EdgeEdge);
  CHECK(sat.indexA == 2);
  CHECK(sat.indexB == 0);
  const ContactManifold m = buildContactManifold(c.a, c.b, sat);
  // Eberly's epsilon inflates the depth by 1e-12 * 4 * 0.5 / |z x x| = 2e-12; rounding of the
  // sqrt(2) geometry adds ~1e-16.
  const double tol = 1e-11;
  CHECK(m.depth == Approx(0.01).margin(tol));
  CHECK((m.normal - Vec3::UnitY()).norm() < kRound);
  REQUIRE(m.count == 1);
  CHECK((m.points[0].position - Vec3(0, std::sqrt(0.5) - 0.005, -0.05)).norm() < tol);
  CHECK(m.points[0].featureId >> 13 == 1u);
}

TEST_CASE("Nearly parallel boxes (1e-9 rad) give a finite face contact, not an edge contact",
          "[collision][manifold]") {
  const Obb a = cube(Vec3::Zero());
  const Obb b = cube(Vec3(0.1, 0.99, 0.05), rotation(1e-9, Vec3(1, 0.3, 1)));
  const SeparatingAxisResult sat = separatingAxisTest(a, b);
  CHECK(sat.kind != AxisKind::EdgeEdge);
  CHECK(std::isfinite(sat.depth));
  CHECK(sat.normal.allFinite());
  // The tilt moves B's bottom corners by at most 1e-9 * 0.87 m.
  CHECK((sat.normal - Vec3::UnitY()).norm() < 1e-8);
  CHECK(sat.depth == Approx(0.01).margin(1e-8));
  const ContactManifold m = buildContactManifold(a, b, sat);
  REQUIRE(m.count == 4);
  for (int k = 0; k < m.count; ++k) {
    CHECK(m.points[k].position.allFinite());
    CHECK(m.points[k].depth == Approx(0.01).margin(1e-8));
  }
}

TEST_CASE("Clipping to 8 points keeps 4: the deepest and a near-maximal area",
          "[collision][manifold][reduction]") {
  // B, a unit cube turned 45 degrees about y, lies on A, whose 1.2 m square top is larger than
  // B's face (so A's face is the reference) but smaller than B's diamond (half diagonal 0.707):
  // the diamond clipped by the square is an octagon. A 2 mrad tilt gives each corner its own
  // depth, between 0.9 and 1.1 cm.
  const Obb a{Vec3::Zero(), Mat3::Identity(), Vec3(0.6, 0.5, 0.6)};
  const Mat3 R = rotation(2e-3, Vec3(1, 0, 0.4)) * rotation(kPi / 4, Vec3::UnitY());
  const Obb b = cube(Vec3(0, 0.49, 0) + R * Vec3(0, 0.5, 0), R);

  // Reference octagon, found without clipping: every crossing of one of B's bottom edges with
  // one of A's side planes, and every bottom corner of B inside A's top square (none here).
  std::vector<Vec3> octagon;
  const std::array<int, 4> bottom = {0, 1, 5, 4};  // B's -y face, cyclic
  for (int e = 0; e < 4; ++e) {
    const Vec3 p = b.corner(bottom[e]);
    const Vec3 q = b.corner(bottom[(e + 1) % 4]);
    for (int axis : {0, 2})
      for (double side : {-0.6, 0.6}) {
        const double t = (side - p[axis]) / (q[axis] - p[axis]);
        const Vec3 x = p + t * (q - p);
        if (t > 0 && t < 1 && std::abs(x[2 - axis]) <= 0.6) octagon.push_back(x);
      }
  }
  REQUIRE(octagon.size() == 8);
  std::vector<Vec3> expected;  // midway between B's face and A's top (y = 0.5)
  int deepest = 0;
  for (const Vec3& x : octagon) {
    expected.push_back(Vec3(x.x(), 0.5 * (x.y() + 0.5), x.z()));
    if (x.y() < octagon[deepest].y()) deepest = static_cast<int>(expected.size()) - 1;
  }

  const ContactManifold m = collideBoxes(a, b);
  REQUIRE(m.kind == AxisKind::FaceA);
  REQUIRE(m.count == 4);
  const std::vector<Vec3> kept = positions(m);
  // Every kept point is an octagon corner (the line crossings agree to rounding, ~1e-15 m) ...
  for (const Vec3& p : kept) {
    bool found = false;
    for (const Vec3& x : expected) found = found || (p - x).norm() < kRound;
    CHECK(found);
  }
  // ... the deepest is among them, and so is the depth ...
  bool hasDeepest = false;
  for (const Vec3& p : kept) hasDeepest = hasDeepest || (p - expected[deepest]).norm() < kRound;
  CHECK(hasDeepest);
  CHECK(m.depth == Approx(0.5 - octagon[deepest].y()).margin(kRound));
  // ... and the quadrilateral is nearly the largest containing it (four neighbouring corners
  // would cover about a third of it).
  double best = 0.0;
  for (int i = 0; i < 8; ++i)
    for (int j = i + 1; j < 8; ++j)
      for (int k = j + 1; k < 8; ++k)
        if (i != deepest && j != deepest && k != deepest)
          best = std::max(best, quadArea({expected[deepest], expected[i], expected[j], expected[k]},
                                         Vec3::UnitY()));
  CHECK(quadArea(kept, Vec3::UnitY()) >= 0.95 * best);
}

TEST_CASE("Feature ids are distinct within a manifold and unchanged by a small slide",
          "[collision][manifold][features]") {
  const Obb a = cube(Vec3::Zero());
  for (double turn : {0.0, kPi / 4}) {
    INFO("turn " << turn);
    const Mat3 R = rotation(turn, Vec3::UnitY());
    const ContactManifold m0 = collideBoxes(a, cube(Vec3(0.3, 0.99, 0.2), R));
    const ContactManifold m1 = collideBoxes(a, cube(Vec3(0.301, 0.99, 0.199), R));
    REQUIRE(m0.count == 4);
    REQUIRE(m1.count == 4);
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j) CHECK(m0.points[i].featureId != m0.points[j].featureId);
    for (int k = 0; k < 4; ++k) {
      CHECK(m0.points[k].featureId == m1.points[k].featureId);
      // A crossing of a 45-degree edge with a side plane slides by |dx| + |dz| = 2 mm.
      CHECK((m0.points[k].position - m1.points[k].position).norm() <= 2e-3 + kRound);
    }
  }
}

TEST_CASE("Equal boxes stacked flush in any orientation keep the four corners of the face",
          "[collision][manifold][robustness]") {
  // The incident face coincides with the reference face, so its vertices lie on the side
  // planes, where rounding scatters them ~1e-17 m to either side. One cut off just outside
  // used to leave two crossings a rounding apart: 5 points, all depths tied, and the reduction
  // to 4 kept both crossings and dropped a real corner (75 % of the face in 7 % of these
  // stacks). The four corners span the whole face, 4 h_x h_z; rounding moves them ~1e-15 m.
  testing::SeededRandom random(2020);
  for (int trial = 0; trial < 500; ++trial) {
    INFO("trial " << trial);
    const Mat3 Q = random.rotation().toRotationMatrix();
    const Vec3 x = random.vector(-3, 3);
    const Vec3 h(random.uniform(0.2, 1.0), random.uniform(0.2, 1.0), random.uniform(0.2, 1.0));
    const Obb a{x, Q, h};
    const Obb b{Vec3(x + Q * Vec3(0, 2 * h.y(), 0)), Q, h};
    const ContactManifold m = collideBoxes(a, b, 1e-3);
    REQUIRE(m.count == 4);
    const double face = 4 * h.x() * h.z();
    CHECK(std::abs(quadArea(positions(m), m.normal)) == Approx(face).epsilon(1e-9));
    CHECK(contactArea(a, b, separatingAxisTest(a, b), 1e-3).size() == 4);
  }
}

// ---------------------------------------------------------------------------------------------
// Symmetries
// ---------------------------------------------------------------------------------------------

TEST_CASE("Swapping the boxes keeps the depth, negates the normal and keeps the points",
          "[collision][symmetry]") {
  std::vector<Config> configs = configurations();
  // Equal flush cubes, one turned 45 degrees: the two faces tie in every respect but height.
  configs.push_back({"turned cube", cube(Vec3::Zero()),
                     cube(Vec3(0, 0.99, 0), rotation(kPi / 4, Vec3::UnitY()))});
  testing::SeededRandom random(7);
  for (int trial = 0; trial < 200; ++trial) {
    const Obb a{random.vector(-0.5, 0.5), random.rotation().toRotationMatrix(), random.vector(0.2, 1.0)};
    const Obb b{random.vector(-0.5, 0.5), random.rotation().toRotationMatrix(), random.vector(0.2, 1.0)};
    configs.push_back({"random", a, b});
  }
  int compared = 0;
  for (const Config& c : configs) {
    INFO(c.name << " #" << compared);
    const ContactManifold ab = collideBoxes(c.a, c.b);
    const ContactManifold ba = collideBoxes(c.b, c.a);
    // Designed to be bit-exact (the swapped sums are the same sums commuted); 1e-12 is the
    // promise.
    CHECK(ab.depth == Approx(ba.depth).margin(kRound));
    CHECK((ab.normal + ba.normal).norm() < kRound);
    CHECK(samePointSet(positions(ab), positions(ba), kRound));
    ++compared;
  }
}

TEST_CASE("Swapping boxes whose face axis is perpendicular to the line of centres negates the normal",
          "[collision][symmetry]") {
  // Equal plates side by side in one plane, overlapping by more than their thickness: the
  // thickness axis wins with D . n = 0, and both plates' faces tie in area, height and depth.
  // The axis' sign used to come from the label (A's axis as is), the same for both calls.
  const Vec3 h(1.0, 0.05, 1.0);
  const Mat3 turned = rotation(0.3, Vec3::UnitY());
  for (const Vec3& offset : {Vec3(0.3, 0, 0.2), Vec3(-0.3, 0, 0.2), Vec3(0, 0, -0.4)}) {
    for (const Mat3& axes : {Mat3(Mat3::Identity()), turned}) {
      INFO("offset " << offset.transpose());
      const Obb a{Vec3::Zero(), Mat3::Identity(), h};
      const Obb b{offset, axes, h};
      const SeparatingAxisResult ab = separatingAxisTest(a, b);
      const SeparatingAxisResult ba = separatingAxisTest(b, a);
      REQUIRE(std::abs(ab.normal.y()) == 1.0);
      CHECK(ab.depth == ba.depth);
      CHECK(ab.normal == Vec3(-ba.normal));
      // One box gives the reference face in both calls: FaceA in one, FaceB in the other.
      CHECK(ab.kind != ba.kind);
      CHECK(samePointSet(positions(collideBoxes(a, b)), positions(collideBoxes(b, a)), kRound));
    }
  }
}

TEST_CASE("A box apart from a wide ground's edge along an edge axis is not intersecting at depth > 0",
          "[collision][sat][robustness]") {
  // A unit cube in a random orientation, its lowest corner 2e-8 m below the top of a ground
  // 100 m wide (face tie width 5e-8 m), slid out over the ground's edge until the boxes part.
  // Just past that point an edge-edge axis separates them by a rounding while every face axis
  // still overlaps: the face used to be reported with depth 2e-8 > 0 and intersecting false.
  const Obb ground{Vec3(0, -0.5, 0), Mat3::Identity(), Vec3(50, 0.5, 50)};
  testing::SeededRandom random(3);
  for (int trial = 0; trial < 20; ++trial) {
    const Mat3 R = random.rotation().toRotationMatrix();
    double lowest = 0.0;
    for (int k = 0; k < 8; ++k) lowest = std::min(lowest, (R * cube(Vec3::Zero()).corner(k)).y());
    const auto at = [&](double x) { return cube(Vec3(x, -lowest - 2e-8, 0.0), R); };
    double in = 49.0, out = 52.0;  // intersecting at x = in, apart at x = out
    for (int k = 0; k < 100; ++k) {
      const double mid = 0.5 * (in + out);
      (separatingAxisTest(ground, at(mid)).intersecting ? in : out) = mid;
    }
    INFO("trial " << trial << " x " << out);
    const SeparatingAxisResult sat = separatingAxisTest(ground, at(out));
    CHECK_FALSE(sat.intersecting);
    CHECK(sat.depth <= 0.0);
    CHECK(collideBoxes(ground, at(out)).count == 0);
  }
}

TEST_CASE("Moving both boxes rigidly moves the contact with them", "[collision][symmetry]") {
  std::vector<Config> configs = configurations();
  testing::SeededRandom random(1984);
  for (int trial = 0; trial < 50; ++trial) {
    const Obb a{random.vector(-0.5, 0.5), random.rotation().toRotationMatrix(), random.vector(0.2, 1.0)};
    const Obb b{random.vector(-0.5, 0.5), random.rotation().toRotationMatrix(), random.vector(0.2, 1.0)};
    configs.push_back({"random", a, b});
  }
  for (const Config& c : configs) {
    const Mat3 Q = random.rotation().toRotationMatrix();
    const Vec3 t = random.vector(-10, 10);
    INFO(c.name);
    const ContactManifold m = collideBoxes(c.a, c.b);
    const ContactManifold mq = collideBoxes(moved(c.a, Q, t), moved(c.b, Q, t));
    // Rotating and translating by 10 m rounds every coordinate at ~2e-15 m; clipping divides by
    // sines of edge-plane angles, far from 1e-6 in these scenes: 1e-9 leaves a wide margin.
    CHECK(m.depth == Approx(mq.depth).margin(1e-9));
    CHECK((Q * m.normal - mq.normal).norm() < 1e-9);
    std::vector<Vec3> expected;
    for (const Vec3& p : positions(m)) expected.push_back(Q * p + t);
    CHECK(samePointSet(expected, positions(mq), 1e-9));
  }
}

// ---------------------------------------------------------------------------------------------
// Broad phase
// ---------------------------------------------------------------------------------------------

TEST_CASE("Box bounds are the extremes of its corners", "[collision][broad_phase]") {
  testing::SeededRandom random(99);
  for (int trial = 0; trial < 20; ++trial) {
    const Obb box{random.vector(-3, 3), random.rotation().toRotationMatrix(), random.vector(0.1, 2.0)};
    Vec3 lo, hi;
    obbBounds(box, 0.25, lo, hi);
    Vec3 cLo = box.corner(0), cHi = box.corner(0);
    for (int k = 1; k < 8; ++k) {
      cLo = cLo.cwiseMin(box.corner(k));
      cHi = cHi.cwiseMax(box.corner(k));
    }
    CHECK((lo - (cLo - Vec3::Constant(0.25))).norm() < kRound);
    CHECK((hi - (cHi + Vec3::Constant(0.25))).norm() < kRound);
  }
}

TEST_CASE("Candidate pairs come in increasing order and skip two immovable bodies",
          "[collision][broad_phase]") {
  World world;
  world.addGround(0.0, 5.0);                                    // 0: y in [-1, 0]
  RigidBody wall = RigidBody::immovableBox(Vec3(0.1, 2.0, 5.0));
  wall.s.x = Vec3(5.0, 1.5, 0.0);                               // 1: overlaps the ground
  world.add(wall, "wall");
  auto boxAt = [&](const Vec3& x, const std::string& name) {
    RigidBody body = RigidBody::box(Vec3::Constant(0.5), 1.0);
    body.s.x = x;
    return world.add(body, name);
  };
  boxAt(Vec3(0, 0.5, 0), "on_ground");     // 2
  boxAt(Vec3(0, 1.6, 0), "above, 0.1 gap");  // 3
  boxAt(Vec3(4.95, 0.5, 0), "at the wall");  // 4
  boxAt(Vec3(20, 20, 20), "far away");     // 5

  using Pairs = std::vector<std::pair<int, int>>;
  CHECK(candidatePairs(world) == Pairs{{0, 2}, {0, 4}, {1, 4}});
  CHECK(candidatePairs(world, 0.2) == Pairs{{0, 2}, {0, 4}, {1, 4}, {2, 3}});
  // Touching bounds (gap exactly 0) are candidates.
  world.bodies[3].s.x = Vec3(0, 1.5, 0);
  world.bodies[3].updateDerived();
  CHECK(candidatePairs(world) == Pairs{{0, 2}, {0, 4}, {1, 4}, {2, 3}});
}

TEST_CASE("findContacts reports each penetrating pair once with normals from a to b",
          "[collision][broad_phase]") {
  World world;
  world.addGround(0.0, 5.0);  // 0
  auto boxAt = [&](const Vec3& x) {
    RigidBody body = RigidBody::box(Vec3::Constant(0.5), 1.0);
    body.s.x = x;
    return world.add(body, "box");
  };
  boxAt(Vec3(0.1, 1.485, 0));  // 1: on top of box 2, 5 mm into it
  boxAt(Vec3(0, 0.49, 0));     // 2: 1 cm into the ground
  boxAt(Vec3(3, 0.7, 3));      // 3: 2 dm above the ground

  const std::vector<ContactManifold> contacts = findContacts(world);
  REQUIRE(contacts.size() == 2);
  CHECK(contacts[0].a == 0);
  CHECK(contacts[0].b == 2);
  CHECK((contacts[0].normal - Vec3::UnitY()).norm() < kRound);
  CHECK(contacts[0].depth == Approx(0.01).margin(kRound));
  CHECK(contacts[0].count == 4);
  CHECK(contacts[1].a == 1);
  CHECK(contacts[1].b == 2);
  CHECK((contacts[1].normal + Vec3::UnitY()).norm() < kRound);  // from the upper box down
  CHECK(contacts[1].depth == Approx(0.005).margin(kRound));
  CHECK(contacts[1].count == 4);

  CHECK(firstIntersectingPair(world, 0.0) == std::make_pair(0, 2));
  CHECK(firstIntersectingPair(world, 0.02) == std::make_pair(-1, -1));
  // With a 0.25 m margin the hovering box joins, with a negative (gap) depth.
  const std::vector<ContactManifold> near = findContacts(world, 0.25);
  REQUIRE(near.size() == 3);
  CHECK(near[1].a == 0);
  CHECK(near[1].b == 3);
  CHECK(near[1].depth == Approx(-0.2).margin(kRound));
  CHECK(firstIntersectingPair(world, -0.25) == std::make_pair(0, 2));
}

TEST_CASE("The contact area of a cube turned 45 degrees on another is an octagon (thesis 3.2)",
          "[collision][manifold][contact_area]") {
  // Two unit cubes face to face, the upper turned 45° about y: the overlap of the two squares
  // is a regular octagon, all of whose vertices lie on the touching plane y = 1.
  const Obb lower{Vec3(0.0, 0.5, 0.0), Mat3::Identity(), Vec3::Constant(0.5)};
  const Obb upper{Vec3(0.0, 1.5, 0.0),
                  Eigen::AngleAxisd(kPi / 4.0, Vec3::UnitY()).toRotationMatrix(),
                  Vec3::Constant(0.5)};
  const SeparatingAxisResult sat = separatingAxisTest(lower, upper);
  const std::vector<ContactPoint> area = contactArea(lower, upper, sat, 1e-6);
  REQUIRE(area.size() == 8);
  // Octagon of the overlap: vertices at distance 0.5 / cos(22.5°) from the axis.
  const double radius = 0.5 / std::cos(kPi / 8.0);
  for (const ContactPoint& p : area) {
    CHECK(p.position.y() == Approx(1.0).margin(1e-12));
    CHECK(std::hypot(p.position.x(), p.position.z()) == Approx(radius).epsilon(1e-12));
  }
  // The manifold keeps four of them.
  const ContactManifold m = buildContactManifold(lower, upper, sat, 1e-6);
  REQUIRE(m.count == 4);
  for (int k = 0; k < 4; ++k) {
    bool found = false;
    for (const ContactPoint& p : area)
      found = found || (p.position == m.points[k].position && p.featureId == m.points[k].featureId);
    CHECK(found);
  }
}

// ---------------------------------------------------------------------------------------------
// Kept narrow phases
// ---------------------------------------------------------------------------------------------

namespace {
/// Whether two separating-axis results are the same to the last bit in every field.
bool sameResult(const SeparatingAxisResult& x, const SeparatingAxisResult& y) {
  return x.intersecting == y.intersecting && sameBits(x.depth, y.depth) &&
         sameBits(x.normal, y.normal) && x.kind == y.kind && x.indexA == y.indexA &&
         x.indexB == y.indexB;
}

/// configurations(), a cube resting on a ground slab, `extra`, and `count` random pairs of
/// boxes (seeded), overlapping or not.
std::vector<Config> manyConfigurations(const std::vector<Config>& extra, unsigned seed, int count) {
  std::vector<Config> configs = configurations();
  const Obb ground{Vec3(0, -0.5, 0), Mat3::Identity(), Vec3(20, 0.5, 20)};
  configs.push_back({"cube on the ground", ground, cube(Vec3(0.3, 0.5, -2.0))});
  configs.insert(configs.end(), extra.begin(), extra.end());
  testing::SeededRandom random(seed);
  for (int trial = 0; trial < count; ++trial)
    configs.push_back({"random",
                       Obb{random.vector(-0.8, 0.8), random.rotation().toRotationMatrix(), random.vector(0.2, 1.0)},
                       Obb{random.vector(-0.8, 0.8), random.rotation().toRotationMatrix(), random.vector(0.2, 1.0)}});
  return configs;
}
}  // namespace

TEST_CASE("A kept narrow phase is the separating-axis test bit for bit, and runs again once a "
          "box has moved by one rounding",
          "[collision][kept]") {
  // The standard configurations, boxes resting flush (on a ground slab, on an equal cube, side
  // by side: the ties of the face rule), apart, and 400 random pairs overlapping or not.
  const std::vector<Config> configs = manyConfigurations(
      {{"cube on a cube", cube(Vec3::Zero()), cube(Vec3(0.2, 1.0, 0.1))},
       {"side by side", cube(Vec3::Zero()), cube(Vec3(1.0, 0.0, 0.0))},
       {"turned on a cube", cube(Vec3::Zero()), cube(Vec3(0, 0.99, 0), rotation(kPi / 4, Vec3::UnitY()))},
       {"apart", cube(Vec3::Zero()), cube(Vec3(0.3, 1.2, 0.0), rotation(0.4, Vec3(1, 1, 0)))}},
      11, 400);
  KeptNarrowPhase kept;
  int i = 0;
  for (const Config& c : configs) {
    INFO(c.name << " #" << i / 2);
    const int ia = i++, ib = i++;
    const SeparatingAxisResult ab = separatingAxisTest(c.a, c.b);
    const SeparatingAxisResult ba = separatingAxisTest(c.b, c.a);
    const long tests = kept.tests(), reuses = kept.reuses();
    CHECK(sameResult(kept.axis(ia, c.a, ib, c.b), ab));
    CHECK(kept.tests() == tests + 1);
    // Asked again: handed back. The other way round is a pair of its own, tested once.
    CHECK(sameResult(kept.axis(ia, c.a, ib, c.b), ab));
    CHECK(sameResult(kept.axis(ib, c.b, ia, c.a), ba));
    CHECK(sameResult(kept.axis(ib, c.b, ia, c.a), ba));
    CHECK(kept.reuses() == reuses + 2);
    CHECK(kept.tests() == tests + 2);
    // The manifold built from a kept test is collideBoxes'.
    const ContactManifold m = kept.collide(ia, c.a, ib, c.b, 0.01);
    const ContactManifold direct = collideBoxes(c.a, c.b, 0.01);
    REQUIRE(m.count == direct.count);
    CHECK(sameBits(m.depth, direct.depth));
    for (int k = 0; k < m.count; ++k) CHECK(m.points[k].position == direct.points[k].position);
    // One rounding of one coordinate of either box: the test runs again.
    Obb nudged = c.b;
    nudged.center.x() = std::nextafter(nudged.center.x(), 1e9);
    CHECK(sameResult(kept.axis(ia, c.a, ib, nudged), separatingAxisTest(c.a, nudged)));
    CHECK(kept.tests() == tests + 3);
  }
  // A step in which a pair is not asked for forgets it: asked after, its test runs again.
  kept.endStep();  // the step of every pair above
  CHECK(sameResult(kept.axis(0, configs[0].a, 1, configs[0].b),
                   separatingAxisTest(configs[0].a, configs[0].b)));
  const long before = kept.tests();
  kept.endStep();  // pair (0, 1) asked for: kept
  kept.axis(0, configs[0].a, 1, configs[0].b);
  CHECK(kept.tests() == before);
  kept.endStep();  // asked for again in the step that ends: kept
  kept.endStep();  // not asked for: forgotten
  kept.axis(0, configs[0].a, 1, configs[0].b);
  CHECK(kept.tests() == before + 1);
  // Keeping off: every test runs.
  KeptNarrowPhase runAll(false);
  runAll.axis(0, configs[0].a, 1, configs[0].b);
  CHECK(sameResult(runAll.axis(0, configs[0].a, 1, configs[0].b),
                   separatingAxisTest(configs[0].a, configs[0].b)));
  CHECK(runAll.tests() == 2);
  CHECK(runAll.reuses() == 0);
}

namespace {
/// Whether two manifolds are the same to the last bit in every field.
bool sameManifold(const ContactManifold& x, const ContactManifold& y) {
  if (x.a != y.a || x.b != y.b || !sameBits(x.normal, y.normal) || x.kind != y.kind ||
      !sameBits(x.depth, y.depth) || x.count != y.count)
    return false;
  for (int k = 0; k < x.count; ++k)
    if (!sameBits(x.points[k].position, y.points[k].position) ||
        !sameBits(x.points[k].depth, y.points[k].depth) || x.points[k].featureId != y.points[k].featureId)
      return false;
  return true;
}
}  // namespace

TEST_CASE("One clip of a pair gives its manifold for every margin, bit for bit, and a kept "
          "narrow phase clips once for all the margins asked at the same poses",
          "[collision][clip][kept]") {
  // The standard configurations, boxes resting flush or sunk, tilted, edge on edge, apart, and
  // 400 random pairs; margins from 0 to beyond any depth here, so points drop out one by one.
  const std::vector<Config> configs = manyConfigurations(
      {{"tilted on a cube", cube(Vec3::Zero()), cube(Vec3(0.1, 0.999, 0.0), rotation(0.05, Vec3(1, 0, 1)))},
       {"on an edge", cube(Vec3::Zero()),
        cube(Vec3(0, 0.5 + 0.5 * std::sqrt(2.0) - 0.001, 0), rotation(kPi / 4, Vec3::UnitX()))}},
      37, 400);
  const std::vector<double> margins{0.0, 1e-6, 1e-3, 3.2e-3, 0.01, 0.025, 0.1, 0.5, 2.0, 10.0};
  KeptNarrowPhase kept;
  int face = 0, edge = 0, partial = 0;
  for (std::size_t c = 0; c < configs.size(); ++c) {
    const Config& config = configs[c];
    INFO(config.name << " #" << c);
    const SeparatingAxisResult sat = separatingAxisTest(config.a, config.b);
    const ClippedContact clip = clipContact(config.a, config.b, sat);
    const int ia = static_cast<int>(2 * c), ib = ia + 1;
    const long clipsBefore = kept.clips();
    int counts = -1;
    for (const double margin : margins) {
      const ContactManifold direct = buildContactManifold(config.a, config.b, sat, margin);
      CHECK(sameManifold(manifoldWithin(clip, margin), direct));
      CHECK(sameManifold(kept.collide(ia, config.a, ib, config.b, margin), direct));
      if (counts >= 0 && direct.count != counts) ++partial;  // a margin changed the points
      counts = direct.count;
    }
    // One clip for all the margins, if any had points.
    CHECK(kept.clips() - clipsBefore <= 1);
    (sat.kind == AxisKind::EdgeEdge ? edge : face) += 1;
    // Moved by one rounding: a new test and a new clip.
    Obb nudged = config.b;
    nudged.center.x() = std::nextafter(nudged.center.x(), 1e9);
    CHECK(sameManifold(kept.collide(ia, config.a, ib, nudged, 10.0),
                       collideBoxes(config.a, nudged, 10.0)));
  }
  // Both kinds, and margins that keep some points and drop others, were compared.
  CHECK(face > 100);
  CHECK(edge > 10);
  CHECK(partial > 50);
}

TEST_CASE("A batch of kept narrow phases answers as the calls one after another, in any order "
          "and on several threads: the same manifolds, store and counts",
          "[collision][kept][threads]") {
  // Forty boxes of random sizes and turns jumbled over a ground slab: pairs sunk, touching
  // within the margins and apart; six steps in which some boxes stand bitwise still (their
  // tests are handed back), some move by a rounding (tested again) and some by centimetres
  // (pairs that were apart are settled by one axis, or tested).
  testing::SeededRandom random(5);
  World world;
  world.addGround(0.0, 10.0);
  for (int k = 0; k < 40; ++k) {
    RigidBody body = RigidBody::box(random.vector(0.2, 0.6), 1.0);
    body.s.x = random.vector(-1.5, 1.5) + Vec3(0.0, 1.6, 0.0);
    body.s.q = random.rotation();
    body.updateDerived();
    world.add(body, "box");
  }
  // One store asked pair by pair; the same requests in batches whose loop runs the items
  // backwards, and in batches on three threads.
  KeptNarrowPhase serial, backwards, threaded;
  backwards.setLoop([](int count, const std::function<void(int)>& item) {
    for (int k = count - 1; k >= 0; --k) item(k);
  });
  threaded.setLoop([](int count, const std::function<void(int)>& item) {
    parallelFor(count, 3, item);
  });
  const auto counts = [](const KeptNarrowPhase& kept) {
    return std::vector<long>{kept.tests(), kept.reuses(), kept.clips(), kept.axisChecks()};
  };
  for (int step = 0; step < 6; ++step) {
    INFO("step " << step);
    // Each pair near enough once, and some also the other way round (a pair of its own), with
    // margins from 0 to 0.2 m.
    std::vector<KeptNarrowPhase::Request> requests;
    for (const auto& [i, j] : candidatePairs(world, 0.2)) {
      requests.push_back({i, j, 0.05 * ((i + j + step) % 5)});
      if ((i + j) % 3 == 0) requests.push_back({j, i, 0.2});
    }
    std::vector<ContactManifold> expected;
    for (const KeptNarrowPhase::Request& r : requests)
      expected.push_back(serial.collide(r.i, Obb::of(world.bodies[r.i]), r.j,
                                        Obb::of(world.bodies[r.j]), r.margin));
    for (KeptNarrowPhase* batched : {&backwards, &threaded}) {
      std::vector<KeptNarrowPhase::Request>& batch = batched->newBatch();
      batch = requests;
      std::size_t answered = 0;
      bool same = true;
      batched->collideAll(world, [&](std::size_t k, const ContactManifold& m) {
        same = same && k == answered && sameManifold(m, expected[k]);
        ++answered;
      });
      CHECK(answered == requests.size());
      CHECK(same);
      CHECK(counts(*batched) == counts(serial));
      batched->endStep();
    }
    serial.endStep();
    // Every third box stands still; the others move by a rounding or by up to 3 cm.
    for (std::size_t b = 1; b < world.bodies.size(); ++b) {
      RigidBody& body = world.bodies[b];
      if (b % 3 == 0) continue;
      if (b % 3 == 1)
        body.s.x.x() = std::nextafter(body.s.x.x(), 1e9);
      else
        body.s.x += random.vector(-0.03, 0.03);
      body.updateDerived();
    }
  }
  // Every kind of answer was compared: handed back, settled by one axis, tested, clipped.
  const std::vector<long> seen = counts(serial);
  CHECK(seen[0] > 100);
  CHECK(seen[1] > 100);
  CHECK(seen[2] > 50);
  CHECK(seen[3] > 20);
}
