/// \file
/// Convex hulls in the horizontal (xz) plane: what a box rests on seen from above, for the
/// geometric-stability test of \thesis{§5.4} and the support test of DAMPENOBJECTS.
#pragma once

#include <algorithm>
#include <vector>

#include "boxsim/core/math.hpp"

namespace boxsim {

/// A point of the xz plane: (x, z), m.
using Vec2 = Eigen::Vector2d;

/// z component of (a − o) × (b − o) in the xz plane, m²: > 0 when o, a, b turn
/// counter-clockwise, 0 when they are collinear.
inline double cross2(const Vec2& o, const Vec2& a, const Vec2& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

/// Convex hull of xz points, counter-clockwise, collinear and repeated points dropped (Andrew's
/// monotone chain after a lexicographic sort, so the hull is a function of the point set alone,
/// not of its order). Fewer than 3 distinct points come back as they are (sorted): a hull
/// without area.
inline std::vector<Vec2> convexHullXZ(std::vector<Vec2> points) {
  std::sort(points.begin(), points.end(), [](const Vec2& l, const Vec2& r) {
    return l.x() < r.x() || (l.x() == r.x() && l.y() < r.y());
  });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return points;
  std::vector<Vec2> hull(2 * points.size());
  std::size_t n = 0;
  for (const Vec2& p : points) {
    while (n >= 2 && cross2(hull[n - 2], hull[n - 1], p) <= 0.0) --n;
    hull[n++] = p;
  }
  for (std::size_t k = points.size() - 1, lower = n + 1; k-- > 0;) {
    while (n >= lower && cross2(hull[n - 2], hull[n - 1], points[k]) <= 0.0) --n;
    hull[n++] = points[k];
  }
  hull.resize(n - 1);  // the last point repeats the first
  return hull;
}

}  // namespace boxsim
