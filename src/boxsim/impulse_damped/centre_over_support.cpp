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
#include <tuple>

#include "boxsim/collision/xz_hull.hpp"
#include "boxsim/core/math.hpp"

namespace boxsim {
namespace {

using Polygon = SupportTest::Polygon;
using LevelFace = SupportTest::LevelFace;

/// The face of `body` whose outward normal points up (`up` true) or down; an empty outline
/// unless one of the body's axes lies within the aligned angle of y, whose cosine is
/// `alignedCosine`.
LevelFace levelFace(const RigidBody& body, bool up, double alignedCosine) {
  LevelFace face;
  const HorizontalFace h = horizontalFace(body, up);
  if (h.verticality < alignedCosine) return face;
  face.normal = h.normal;
  face.centre = h.centre;
  // The hull of the 4 corners straight into the outline, which has room for 2 × 4 points.
  std::array<Vec2, 4> corners = h.corners;
  face.outline.count = convexHullXZ(corners.data(), corners.size(), face.outline.points.data());
  return face;
}

/// The part of convex polygon `polygon` where the affine function f is >= 0 (one step of
/// Sutherland-Hodgman); empty when there is none. A convex polygon cut by a line gains at most
/// one point.
template <class F>
Polygon clipHalfPlane(const Polygon& polygon, const F& f) {
  // f at every vertex, once (each vertex starts one edge and ends another).
  std::array<double, std::tuple_size_v<decltype(polygon.points)>> values;
  for (std::size_t k = 0; k < polygon.count; ++k) values[k] = f(polygon.points[k]);
  Polygon kept;
  for (std::size_t k = 0; k < polygon.count; ++k) {
    const std::size_t next = k + 1 == polygon.count ? 0 : k + 1;
    const Vec2& p = polygon.points[k];
    const Vec2& q = polygon.points[next];
    const double fp = values[k];
    const double fq = values[next];
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

}  // namespace

SupportTest::Polygon levelContactPatch(const RigidBody& upper, const RigidBody& lower,
                                       const SupportTestParams& params) {
  const double alignedCosine = std::cos(params.alignedAngleDeg * kPi / 180.0);
  const LevelFace bottom = levelFace(upper, false, alignedCosine);
  if (bottom.outline.count == 0) return {};
  const LevelFace top = levelFace(lower, true, alignedCosine);
  if (top.outline.count == 0) return {};
  return contactPatch(bottom, top, params.contactBand);
}

namespace {

/// Whether two manifolds are the same pair with the same normal and points, bit for bit: all
/// the support test reads of a manifold.
bool sameManifold(const ContactManifold& x, const ContactManifold& y) {
  if (x.a != y.a || x.b != y.b || x.count != y.count || !sameBits(x.normal, y.normal)) return false;
  for (int k = 0; k < x.count; ++k)
    if (!sameBits(x.points[k].position, y.points[k].position)) return false;
  return true;
}

/// Whether two sets of parameters are the same, bit for bit.
bool sameParams(const SupportTestParams& x, const SupportTestParams& y) {
  return sameBits(x.supportNormalY, y.supportNormalY) &&
         sameBits(x.alignedAngleDeg, y.alignedAngleDeg) &&
         sameBits(x.contactBand, y.contactBand) && sameBits(x.levelTolerance, y.levelTolerance);
}

}  // namespace

void SupportTest::markChanged(const World& world, const std::vector<ContactManifold>& contacts,
                              const SupportTestParams& params) {
  const std::size_t n = world.bodies.size();
  // Everything is new: another world size, other parameters, or the first call.
  const bool all = !asked_ || n != poses_.size() || !sameParams(params, params_);
  asked_ = true;
  params_ = params;
  poses_.resize(n);
  changed_.assign(n, 0);
  moved_.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const RigidBody& body = world.bodies[i];
    Pose& pose = poses_[i];
    if (all || !sameBits(pose.x, body.s.x) || !sameBits(pose.R, body.R) ||
        !sameBits(pose.halfExtents, body.halfExtents) || pose.immovable != body.immovable) {
      moved_[i] = changed_[i] = 1;
      pose = Pose{body.s.x, body.R, body.halfExtents, body.immovable};
    }
  }
  // A body's verdict reads its manifolds and the poses of the bodies they touch: a manifold
  // not bitwise the last call's of its pair, or a partner that moved, changes it; so does a
  // manifold that is gone (the count of its manifolds differs).
  touching_.assign(n, 0);
  for (const ContactManifold& m : contacts) {
    if (m.count == 0) continue;
    const std::size_t a = static_cast<std::size_t>(m.a), b = static_cast<std::size_t>(m.b);
    ++touching_[a];
    ++touching_[b];
    const int* last = lastOfPair_.find(m.a, m.b);
    if (!last || !sameManifold(last_[static_cast<std::size_t>(*last)], m) || moved_[a] || moved_[b])
      changed_[a] = changed_[b] = 1;
  }
  lastTouching_.resize(n, 0);
  for (std::size_t i = 0; i < n; ++i)
    if (touching_[i] != lastTouching_[i]) changed_[i] = 1;
  // This call's manifolds are the next call's last ones.
  last_.clear();
  lastOfPair_.clear();
  for (const ContactManifold& m : contacts) {
    if (m.count == 0) continue;
    // A pair listed twice: its bodies are asked anew (the lookup above saw one of the two).
    if (lastOfPair_.find(m.a, m.b))
      changed_[static_cast<std::size_t>(m.a)] = changed_[static_cast<std::size_t>(m.b)] = 1;
    lastOfPair_.at(m.a, m.b) = static_cast<int>(last_.size());
    last_.push_back(m);
  }
  lastTouching_.swap(touching_);
}

const std::vector<SupportVerdict>& SupportTest::operator()(
    const World& world, const std::vector<ContactManifold>& contacts,
    const SupportTestParams& params) {
  const std::size_t n = world.bodies.size();
  // Only the bodies whose verdict may differ from the last call's are asked again.
  markChanged(world, contacts, params);
  // A body's level faces, once, and only those a contact asks for: a body meets several
  // others, and a sleeping one (immovable for the step) needs no lower face.
  faces_.resize(2 * n);
  found_.assign(2 * n, 0);
  const double alignedCosine = std::cos(params.alignedAngleDeg * kPi / 180.0);
  const auto faceOf = [&](int body, bool up) -> const LevelFace& {
    const std::size_t k = 2 * static_cast<std::size_t>(body) + (up ? 1 : 0);
    if (!found_[k]) {
      faces_[k] = levelFace(world.bodies[static_cast<std::size_t>(body)], up, alignedCosine);
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
      if (world.bodies[upper].immovable || !changed_[static_cast<std::size_t>(upper)]) continue;
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
  verdicts_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (!changed_[i]) continue;  // the last call's verdict stands
    verdicts_[i] = SupportVerdict{};
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
