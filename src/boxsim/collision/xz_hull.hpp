/// \file
/// The horizontal (xz) plane seen from above: a box's upper or lower face and convex hulls of
/// what a box rests on, for the geometric-stability tests of \thesis{§5.4} (and stability under
/// load) and the support test of DAMPENOBJECTS.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "boxsim/core/math.hpp"
#include "boxsim/core/rigid_body.hpp"

namespace boxsim {

/// A point of the xz plane: (x, z), m.
using Vec2 = Eigen::Vector2d;

/// z component of (a − o) × (b − o) in the xz plane, m²: > 0 when o, a, b turn
/// counter-clockwise, 0 when they are collinear.
inline double cross2(const Vec2& o, const Vec2& a, const Vec2& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

/// Convex hull of the xz points [points, points + count), counter-clockwise, collinear and
/// repeated points dropped (Andrew's monotone chain after a lexicographic sort, so the hull is a
/// function of the point set alone, not of its order), written to `hull`, which has room for
/// 2 count points; returns the hull's size. The points are sorted in place. Fewer than 3
/// distinct points come back as they are (sorted): a hull without area. Allocates nothing.
inline std::size_t convexHullXZ(Vec2* points, std::size_t count, Vec2* hull) {
  std::sort(points, points + count, [](const Vec2& l, const Vec2& r) {
    return l.x() < r.x() || (l.x() == r.x() && l.y() < r.y());
  });
  count = static_cast<std::size_t>(std::unique(points, points + count) - points);
  if (count < 3) {
    std::copy(points, points + count, hull);
    return count;
  }
  std::size_t n = 0;
  for (std::size_t k = 0; k < count; ++k) {
    while (n >= 2 && cross2(hull[n - 2], hull[n - 1], points[k]) <= 0.0) --n;
    hull[n++] = points[k];
  }
  for (std::size_t k = count - 1, lower = n + 1; k-- > 0;) {
    while (n >= lower && cross2(hull[n - 2], hull[n - 1], points[k]) <= 0.0) --n;
    hull[n++] = points[k];
  }
  return n - 1;  // the last point repeats the first
}

/// convexHullXZ of a list of xz points: the hull, as above.
inline std::vector<Vec2> convexHullXZ(std::vector<Vec2> points) {
  std::vector<Vec2> hull(2 * points.size());
  hull.resize(convexHullXZ(points.data(), points.size(), hull.data()));
  return hull;
}

/// The point of the segment from a to b nearest to c (a when the segment is a point).
inline Vec2 nearestOnSegment(const Vec2& a, const Vec2& b, const Vec2& c) {
  const double length2 = (b - a).squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((c - a).dot(b - a) / length2, 0.0, 1.0) : 0.0;
  return a + t * (b - a);
}

/// True when c lies in the convex hull of the `count` points at `points` (sorted in place), or
/// within `tolerance` (m) of it; `hull` has room for 2 count points.
inline bool overHull(Vec2* points, std::size_t count, Vec2* hull, const Vec2& c, double tolerance) {
  const std::size_t size = convexHullXZ(points, count, hull);
  if (size >= 3) {
    for (std::size_t k = 0; k < size; ++k) {
      const Vec2& a = hull[k];
      const Vec2& b = hull[(k + 1) % size];
      if (cross2(a, b, c) < -tolerance * (b - a).norm()) return false;
    }
    return true;
  }
  // A point, or a segment: an edge line or a corner.
  return (nearestOnSegment(hull[0], hull[size - 1], c) - c).norm() <= tolerance;
}

/// The face of a box whose outward normal points most nearly up or down, of any orientation:
/// the face normal to the box's most vertical axis k.
///           v
///           ^
///     1 +---|---+ 0       corner c = centre + su u + sv v (u, v the other two axes times their
///       |   |   |           half extents): 0: (+,+)  1: (-,+)  2: (-,-)  3: (+,-)
///       |   o---|---> u
///       |       |
///     2 +-------+ 3
struct HorizontalFace {
  int axis = 1;                   ///< k, the body axis the face is normal to
  double verticality = 1.0;       ///< |n·y| of its outward normal n: 1 for a level face
  Vec3 centre = Vec3::Zero();     ///< m
  Vec3 normal = Vec3::UnitY();    ///< outward, unit
  std::array<Vec2, 4> corners{};  ///< xz projections, m, numbered as in the diagram
  double smallerHalfExtent = 0.0;  ///< m, the smaller of the face's two half extents
};

/// The upper (`up`) or lower face of `body` (up-to-date R), as HorizontalFace says.
inline HorizontalFace horizontalFace(const RigidBody& body, bool up) {
  HorizontalFace face;
  const int k = body.mostVerticalAxis();
  face.axis = k;
  face.verticality = std::abs(body.R(1, k));
  // The outward normal: along the axis if it points the face's way, against it otherwise.
  const double sense = (body.R(1, k) > 0.0) == up ? 1.0 : -1.0;
  face.normal = sense * body.R.col(k);
  face.centre = body.s.x + sense * body.halfExtents[k] * body.R.col(k);
  const int iu = (k + 1) % 3;
  const int iv = (k + 2) % 3;
  const Vec3 u = body.halfExtents[iu] * body.R.col(iu);
  const Vec3 v = body.halfExtents[iv] * body.R.col(iv);
  static constexpr std::array<double, 4> kSignU = {1.0, -1.0, -1.0, 1.0};
  static constexpr std::array<double, 4> kSignV = {1.0, 1.0, -1.0, -1.0};
  for (int c = 0; c < 4; ++c) {
    const Vec3 p = face.centre + kSignU[c] * u + kSignV[c] * v;
    face.corners[c] = Vec2(p.x(), p.z());
  }
  face.smallerHalfExtent = std::min(body.halfExtents[iu], body.halfExtents[iv]);
  return face;
}

}  // namespace boxsim
