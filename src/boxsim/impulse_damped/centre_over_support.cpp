/// \file
/// The support test of DAMPENOBJECTS (DampingParams::supportTest): is a body's centre of mass
/// over the convex hull of what supports it.
///
/// A box lying face down on another's top face rests on the overlap of the two faces seen from
/// above, the shaded patch; its manifold may hold fewer points (one, for an edge-edge axis):
/// \verbatim
///      upper box's bottom face          z
///        +-----------+                  ^
///        |   lower box's top face       |
///        |     +-----|-----+            +--> x
///        |     |/////|     |
///        |  c  |/////|     |     c over the patch: rests;
///        +-----|-----+     |     c beside it (as here): tips off
///              +-----------+
/// \endverbatim
#include "boxsim/impulse_damped/centre_over_support.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "boxsim/collision/xz_hull.hpp"

namespace boxsim {
namespace {

using Polygon = SupportTest::Polygon;
using LevelFace = SupportTest::LevelFace;

/// The face of `body` whose outward normal points up (`up` true) or down; an empty outline
/// unless one of the body's axes lies within `alignedAngleDeg` of y.
LevelFace levelFace(const RigidBody& body, bool up, double alignedAngleDeg) {
  LevelFace face;
  const HorizontalFace h = horizontalFace(body, up);
  if (h.verticality < std::cos(alignedAngleDeg * kPi / 180.0)) return face;
  face.normal = h.normal;
  face.centre = h.centre;
  std::array<Vec2, 4> corners = h.corners;
  std::array<Vec2, 8> hull;
  face.outline.count = convexHullXZ(corners.data(), corners.size(), hull.data());
  std::copy(hull.begin(), hull.begin() + static_cast<std::ptrdiff_t>(face.outline.count),
            face.outline.points.begin());
  return face;
}

/// The part of convex polygon `polygon` where the affine function f is >= 0 (one step of
/// Sutherland-Hodgman); empty when there is none. A convex polygon cut by a line gains at most
/// one point.
template <class F>
Polygon clipHalfPlane(const Polygon& polygon, const F& f) {
  Polygon kept;
  for (std::size_t k = 0; k < polygon.count; ++k) {
    const Vec2& p = polygon.points[k];
    const Vec2& q = polygon.points[(k + 1) % polygon.count];
    const double fp = f(p);
    const double fq = f(q);
    if (fp >= 0.0) kept.points[kept.count++] = p;
    if ((fp >= 0.0) != (fq >= 0.0)) kept.points[kept.count++] = p + (fp / (fp - fq)) * (q - p);
  }
  return kept;
}

/// Where the face `bottom` of one box lies on the face `top` of another, seen from above: their
/// overlap in xz, cut to where the gap between their planes lies within ±`band` (m; the gap is
/// an affine function of x and z, so each bound is a half plane). Empty when they do not meet.
/// At most 4 + 4 + 2 points: a face's 4 corners and one per cut.
Polygon contactPatch(const LevelFace& bottom, const LevelFace& top, double band) {
  Polygon patch = bottom.outline;
  for (std::size_t e = 0; e < top.outline.count && patch.count > 0; ++e) {
    const Vec2& a = top.outline.points[e];
    const Vec2& b = top.outline.points[(e + 1) % top.outline.count];
    patch = clipHalfPlane(patch, [&](const Vec2& p) { return cross2(a, b, p); });
  }
  if (patch.count > 0)
    patch = clipHalfPlane(patch, [&](const Vec2& p) {
      return band - (bottom.heightAt(p) - top.heightAt(p));
    });
  if (patch.count > 0)  // and not sunk deeper than the band: the faces of two neighbours
    patch = clipHalfPlane(patch, [&](const Vec2& p) {
      return band + (bottom.heightAt(p) - top.heightAt(p));
    });
  return patch;
}

/// True when c lies in the convex hull of the `count` points at `points` (sorted in place), or
/// within `tolerance` (m) of it; `hull` has room for 2 count points.
bool overHull(Vec2* points, std::size_t count, Vec2* hull, const Vec2& c, double tolerance) {
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
  const Vec2& a = hull[0];
  const Vec2& b = hull[size - 1];
  const double length2 = (b - a).squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((c - a).dot(b - a) / length2, 0.0, 1.0) : 0.0;
  return (a + t * (b - a) - c).norm() <= tolerance;
}

}  // namespace

const std::vector<SupportVerdict>& SupportTest::operator()(
    const World& world, const std::vector<ContactManifold>& contacts,
    const SupportTestParams& params) {
  const std::size_t n = world.bodies.size();
  // A body's level faces, once, and only those a contact asks for: a body meets several
  // others, and a sleeping one (immovable for the step) needs no lower face.
  faces_.resize(2 * n);
  found_.assign(2 * n, 0);
  const auto faceOf = [&](int body, bool up) -> const LevelFace& {
    const std::size_t k = 2 * static_cast<std::size_t>(body) + (up ? 1 : 0);
    if (!found_[k]) {
      faces_[k] = levelFace(world.bodies[static_cast<std::size_t>(body)], up, params.alignedAngleDeg);
      found_[k] = 1;
    }
    return faces_[k];
  };
  // The support points of every body, each tagged with its body, in the order found.
  points_.clear();
  // Per body: the lowest and highest point of its supporting top faces over their patches, m,
  // and whether every support so far was such a face.
  lowest_.assign(n, std::numeric_limits<double>::infinity());
  highest_.assign(n, -std::numeric_limits<double>::infinity());
  facesOnly_.assign(n, 1);
  for (const ContactManifold& m : contacts) {
    if (m.count == 0) continue;
    for (const int upper : {m.a, m.b}) {
      if (world.bodies[upper].immovable) continue;
      const int lower = upper == m.b ? m.a : m.b;
      // A face down on a face up: where the two faces touch, whatever axis the narrow phase took
      // for the pair (a side face's, when a corner of one lies near the rim of the other).
      const LevelFace& bottom = faceOf(upper, false);
      const LevelFace& top = faceOf(lower, true);
      if (bottom.outline.count > 0 && top.outline.count > 0) {
        const Polygon patch = contactPatch(bottom, top, params.contactBand);
        if (patch.count > 0) {
          for (std::size_t k = 0; k < patch.count; ++k) {
            const Vec2& p = patch.points[k];
            points_.emplace_back(upper, p);
            lowest_[upper] = std::min(lowest_[upper], top.heightAt(p));
            highest_[upper] = std::max(highest_[upper], top.heightAt(p));
          }
          continue;
        }
      }
      // The normal runs from a to b; seen from `upper` it must point up, from the other body to it.
      const double up = upper == m.b ? m.normal.y() : -m.normal.y();
      if (up <= params.supportNormalY) continue;
      // Any other contact: where the manifold touches.
      facesOnly_[upper] = 0;
      for (int k = 0; k < m.count; ++k)
        points_.emplace_back(upper, Vec2(m.points[k].position.x(), m.points[k].position.z()));
    }
  }
  // The points body by body (a counting sort, in the order found).
  start_.assign(n + 1, 0);
  for (const auto& [body, p] : points_) ++start_[static_cast<std::size_t>(body) + 1];
  std::size_t most = 0;
  for (std::size_t i = 0; i < n; ++i) {
    most = std::max(most, start_[i + 1]);
    start_[i + 1] += start_[i];
  }
  grouped_.resize(points_.size());
  hull_.resize(2 * most);
  {
    std::vector<std::size_t>& next = start_;  // advanced per point, then restored below
    for (const auto& [body, p] : points_) grouped_[next[static_cast<std::size_t>(body)]++] = p;
    // Each start was advanced by its body's count: now start_[i] is body i's end.
    for (std::size_t i = n; i-- > 0;) next[i + 1] = next[i];
    next[0] = 0;
  }
  constexpr double kTolerance = 1e-9;  // m: rounding, and a centre exactly over an edge
  verdicts_.assign(n, SupportVerdict{});
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t count = start_[i + 1] - start_[i];
    if (count == 0) continue;
    const Vec2 c(world.bodies[i].s.x.x(), world.bodies[i].s.x.z());
    verdicts_[i].over = overHull(grouped_.data() + start_[i], count, hull_.data(), c, kTolerance);
    verdicts_[i].level = facesOnly_[i] && highest_[i] - lowest_[i] <= params.levelTolerance;
  }
  return verdicts_;
}

std::vector<SupportVerdict> centreOverSupport(const World& world,
                                              const std::vector<ContactManifold>& contacts,
                                              const SupportTestParams& params) {
  SupportTest test;
  return test(world, contacts, params);
}

}  // namespace boxsim
