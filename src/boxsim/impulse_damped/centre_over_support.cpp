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

/// A face of a box whose outward normal lies within the aligned angle of +y or −y.
struct LevelFace {
  std::vector<Vec2> outline;  ///< xz projection, counter-clockwise; empty: no such face
  Vec3 centre = Vec3::Zero();  ///< m
  Vec3 normal = Vec3::UnitY();  ///< outward, unit
  /// Height of the face's plane above the xz point p, m.
  double heightAt(const Vec2& p) const {
    return centre.y() - (normal.x() * (p.x() - centre.x()) + normal.z() * (p.y() - centre.z())) /
                            normal.y();
  }
};

/// The face of `body` whose outward normal points up (`up` true) or down; an empty outline
/// unless one of the body's axes lies within `alignedAngleDeg` of y.
LevelFace levelFace(const RigidBody& body, bool up, double alignedAngleDeg) {
  LevelFace face;
  const HorizontalFace h = horizontalFace(body, up);
  if (h.verticality < std::cos(alignedAngleDeg * kPi / 180.0)) return face;
  face.normal = h.normal;
  face.centre = h.centre;
  face.outline = convexHullXZ(std::vector<Vec2>(h.corners.begin(), h.corners.end()));
  return face;
}

/// The part of convex polygon `polygon` where the affine function f is >= 0 (one step of
/// Sutherland-Hodgman); empty when there is none.
template <class F>
std::vector<Vec2> clipHalfPlane(const std::vector<Vec2>& polygon, const F& f) {
  std::vector<Vec2> kept;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const Vec2& p = polygon[k];
    const Vec2& q = polygon[(k + 1) % polygon.size()];
    const double fp = f(p);
    const double fq = f(q);
    if (fp >= 0.0) kept.push_back(p);
    if ((fp >= 0.0) != (fq >= 0.0)) kept.push_back(p + (fp / (fp - fq)) * (q - p));
  }
  return kept;
}

/// Where the face `bottom` of one box lies on the face `top` of another, seen from above: their
/// overlap in xz, cut to where the gap between their planes lies within ±`band` (m; the gap is
/// an affine function of x and z, so each bound is a half plane). Empty when they do not meet.
std::vector<Vec2> contactPatch(const LevelFace& bottom, const LevelFace& top, double band) {
  std::vector<Vec2> patch = bottom.outline;
  for (std::size_t e = 0; e < top.outline.size() && !patch.empty(); ++e) {
    const Vec2& a = top.outline[e];
    const Vec2& b = top.outline[(e + 1) % top.outline.size()];
    patch = clipHalfPlane(patch, [&](const Vec2& p) { return cross2(a, b, p); });
  }
  if (!patch.empty())
    patch = clipHalfPlane(patch, [&](const Vec2& p) {
      return band - (bottom.heightAt(p) - top.heightAt(p));
    });
  if (!patch.empty())  // and not sunk deeper than the band: the faces of two neighbours
    patch = clipHalfPlane(patch, [&](const Vec2& p) {
      return band + (bottom.heightAt(p) - top.heightAt(p));
    });
  return patch;
}

/// True when c lies in the convex hull of `points`, or within `tolerance` (m) of it.
bool overHull(const std::vector<Vec2>& points, const Vec2& c, double tolerance) {
  const std::vector<Vec2> hull = convexHullXZ(points);
  if (hull.size() >= 3) {
    for (std::size_t k = 0; k < hull.size(); ++k) {
      const Vec2& a = hull[k];
      const Vec2& b = hull[(k + 1) % hull.size()];
      if (cross2(a, b, c) < -tolerance * (b - a).norm()) return false;
    }
    return true;
  }
  // A point, or a segment: an edge line or a corner.
  const Vec2& a = hull.front();
  const Vec2& b = hull.back();
  const double length2 = (b - a).squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((c - a).dot(b - a) / length2, 0.0, 1.0) : 0.0;
  return (a + t * (b - a) - c).norm() <= tolerance;
}

}  // namespace

std::vector<SupportVerdict> centreOverSupport(const World& world,
                                              const std::vector<ContactManifold>& contacts,
                                              const SupportTestParams& params) {
  const std::size_t n = world.bodies.size();
  // A body's level faces, once, and only those a contact asks for: a body meets several
  // others, and a sleeping one (immovable for the step) needs no lower face.
  std::vector<LevelFace> faces(2 * n);
  std::vector<char> found(2 * n, 0);
  const auto faceOf = [&](int body, bool up) -> const LevelFace& {
    const std::size_t k = 2 * static_cast<std::size_t>(body) + (up ? 1 : 0);
    if (!found[k]) {
      faces[k] = levelFace(world.bodies[static_cast<std::size_t>(body)], up, params.alignedAngleDeg);
      found[k] = 1;
    }
    return faces[k];
  };
  std::vector<std::vector<Vec2>> support(n);
  // Per body: the lowest and highest point of its supporting top faces over their patches, m,
  // and whether every support so far was such a face.
  std::vector<double> lowest(n, std::numeric_limits<double>::infinity());
  std::vector<double> highest(n, -std::numeric_limits<double>::infinity());
  std::vector<char> facesOnly(n, 1);
  for (const ContactManifold& m : contacts) {
    if (m.count == 0) continue;
    for (const int upper : {m.a, m.b}) {
      if (world.bodies[upper].immovable) continue;
      const int lower = upper == m.b ? m.a : m.b;
      std::vector<Vec2>& points = support[upper];
      // A face down on a face up: where the two faces touch, whatever axis the narrow phase took
      // for the pair (a side face's, when a corner of one lies near the rim of the other).
      const LevelFace& bottom = faceOf(upper, false);
      const LevelFace& top = faceOf(lower, true);
      if (!bottom.outline.empty() && !top.outline.empty()) {
        const std::vector<Vec2> patch = contactPatch(bottom, top, params.contactBand);
        if (!patch.empty()) {
          points.insert(points.end(), patch.begin(), patch.end());
          for (const Vec2& p : patch) {
            lowest[upper] = std::min(lowest[upper], top.heightAt(p));
            highest[upper] = std::max(highest[upper], top.heightAt(p));
          }
          continue;
        }
      }
      // The normal runs from a to b; seen from `upper` it must point up, from the other body to it.
      const double up = upper == m.b ? m.normal.y() : -m.normal.y();
      if (up <= params.supportNormalY) continue;
      // Any other contact: where the manifold touches.
      facesOnly[upper] = 0;
      for (int k = 0; k < m.count; ++k)
        points.emplace_back(m.points[k].position.x(), m.points[k].position.z());
    }
  }
  constexpr double kTolerance = 1e-9;  // m: rounding, and a centre exactly over an edge
  std::vector<SupportVerdict> verdicts(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (support[i].empty()) continue;
    const Vec2 c(world.bodies[i].s.x.x(), world.bodies[i].s.x.z());
    verdicts[i].over = overHull(support[i], c, kTolerance);
    verdicts[i].level = facesOnly[i] && highest[i] - lowest[i] <= params.levelTolerance;
  }
  return verdicts;
}

}  // namespace boxsim
