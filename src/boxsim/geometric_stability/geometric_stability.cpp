/// \file
/// \alg{SETGEOMETRICALLYSTABLE} (\thesis{§5.4}), step by step.
///
/// The thesis sweeps the contact points from the lowest up, so that the body under a contact
/// has its final verdict before the body over it is judged. The two main things the pseudocode
/// leaves open are settled so (the DEVIATION comments give these and the others, with reasons):
///  - which body is "top": the one the manifold normal points to when the normal is along y;
///    a contact whose normal is off the y axis has no top and rules out both its bodies;
///  - the verdict must not depend on the order in which contacts of equal height are met, so a
///    body ruled out once stays ruled out.
#include "boxsim/geometric_stability/geometric_stability.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>

#include "boxsim/collision/xz_hull.hpp"

namespace boxsim {
namespace {

using BottomFace = GeometricStability::BottomFace;
using BodyMarks = GeometricStability::BodyMarks;
using VerticalContact = GeometricStability::VerticalContact;

/// The face of `body` whose outward normal points most nearly down.
BottomFace bottomFaceOf(const RigidBody& body, const GeometricStabilityParams& params) {
  const HorizontalFace bottom = horizontalFace(body, /*up=*/false);
  BottomFace face;
  face.level = 1.0 - bottom.verticality <= params.normalTolerance;
  face.corners = bottom.corners;
  face.tolerance = params.cornerTolerance * bottom.smallerHalfExtent;
  return face;
}

/// A direction along ±y within the tolerance (the "equivalent" of SETGEOMETRICALLYSTABLE L13 and
/// L19).
bool alongY(const Vec3& n, const GeometricStabilityParams& params) {
  return 1.0 - std::abs(n.y()) <= params.normalTolerance;
}

/// SETGEOMETRICALLYSTABLE L6: the points of the vertical contacts, lowest first; equal heights in
/// order of the bottom body, the top body, then the input order, so the order is a function of the
/// input alone. The verdict does not depend on that tie order (see the sweep).
void sortContactPointsAscending(const std::vector<ContactManifold>& contacts,
                                const GeometricStabilityParams& params,
                                std::vector<VerticalContact>& sorted) {
  sorted.clear();
  for (int m = 0; m < static_cast<int>(contacts.size()); ++m) {
    const ContactManifold& c = contacts[m];
    if (!alongY(c.normal, params)) continue;
    // The normal runs from a to b: when it points up, b lies on top of a.
    const bool bOnTop = c.normal.y() > 0.0;
    for (int k = 0; k < c.count; ++k) {
      const Vec3& p = c.points[k].position;
      sorted.push_back({p.y(), bOnTop ? c.a : c.b, bOnTop ? c.b : c.a, m, k, Vec2(p.x(), p.z())});
    }
  }
  const auto key = [](const VerticalContact& c) {
    return std::make_tuple(c.height, c.bottom, c.top, c.manifold, c.point);
  };
  std::sort(sorted.begin(), sorted.end(),
            [&](const VerticalContact& l, const VerticalContact& r) { return key(l) < key(r); });
}

/// True when every corner of `face` lies in the convex hull of `support`, or within
/// face.tolerance outside it. A hull of fewer than 3 points has no area and covers nothing.
/// `points` and `hull` are working lists.
bool hullCoversFace(const std::vector<Vec2>& support, const BottomFace& face,
                    std::vector<Vec2>& points, std::vector<Vec2>& hull) {
  points.assign(support.begin(), support.end());
  hull.resize(2 * points.size());
  const std::size_t size = convexHullXZ(points.data(), points.size(), hull.data());
  if (size < 3) return false;
  for (const Vec2& q : face.corners) {
    for (std::size_t i = 0; i < size; ++i) {
      const Vec2& p0 = hull[i];
      const Vec2& p1 = hull[(i + 1) % size];
      // Signed distance of q to the left of the edge p0 -> p1 (inside is to the left).
      if (cross2(p0, p1, q) < -face.tolerance * (p1 - p0).norm()) return false;
    }
  }
  return true;
}

void checkInput(const World& world, const std::vector<ContactManifold>& contacts,
                const GeometricStabilityParams& params) {
  if (!std::isfinite(params.normalTolerance) || params.normalTolerance < 0.0 ||
      params.normalTolerance >= 1.0)
    throw std::invalid_argument("geometric stability: normalTolerance must lie in [0, 1)");
  if (!std::isfinite(params.cornerTolerance) || params.cornerTolerance < 0.0)
    throw std::invalid_argument("geometric stability: cornerTolerance must be finite and >= 0");
  const int n = static_cast<int>(world.bodies.size());
  for (const ContactManifold& c : contacts)
    if (c.a < 0 || c.a >= n || c.b < 0 || c.b >= n || c.count < 0 || c.count > 4)
      throw std::invalid_argument("geometric stability: a contact manifold names body " +
                                  std::to_string(c.a) + " or " + std::to_string(c.b) +
                                  " (or has " + std::to_string(c.count) +
                                  " points) in a world of " + std::to_string(n) + " bodies");
}

}  // namespace

std::string geometricStabilityModeName(GeometricStabilityMode mode) {
  switch (mode) {
    case GeometricStabilityMode::Off: return "off";
    case GeometricStabilityMode::Thesis: return "thesis";
    case GeometricStabilityMode::UnderLoad: return "under_load";
  }
  throw std::invalid_argument("geometric stability: unknown mode");
}

GeometricStabilityMode parseGeometricStabilityMode(const std::string& name) {
  for (const GeometricStabilityMode mode : {GeometricStabilityMode::Off, GeometricStabilityMode::Thesis,
                                            GeometricStabilityMode::UnderLoad})
    if (name == geometricStabilityModeName(mode)) return mode;
  throw std::invalid_argument("unknown geometric stability '" + name +
                              "'; known: off, thesis, under_load");
}

std::vector<char> setGeometricallyStable(const World& world,
                                         const std::vector<ContactManifold>& contacts,
                                         const GeometricStabilityParams& params) {
  GeometricStability test;
  return test(world, contacts, params);
}

const std::vector<char>& GeometricStability::operator()(
    const World& world, const std::vector<ContactManifold>& contacts,
    const GeometricStabilityParams& params) {
  checkInput(world, contacts, params);
  const int n = static_cast<int>(world.bodies.size());

  // SETGEOMETRICALLYSTABLE L1-L5: bodies of infinite mass are stable, every other body starts out
  // unstable.
  std::vector<char>& stable = stable_;
  stable.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) stable[i] = world.bodies[i].immovable ? 1 : 0;

  // The lists of the last call, emptied: each keeps the room it had.
  std::vector<BodyMarks>& marks = marks_;
  marks.resize(static_cast<std::size_t>(n));
  for (BodyMarks& m : marks) {
    m.corners = {};
    m.support.clear();
    m.ruledOut = false;
  }
  std::vector<BottomFace>& bottom = bottom_;
  bottom.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) bottom[i] = bottomFaceOf(world.bodies[i], params);

  // SETGEOMETRICALLYSTABLE L19-L20: contacts whose normal is off the y axis.
  // DEVIATION(SETGEOMETRICALLYSTABLE L19-L20): applied to both bodies, and before the sweep. §5.4
  // asks that all of a body's contact normals be along ±y; a side contact has no top body, so
  // applying L20 to "the top object" alone would rule out one of the two neighbours at random. And
  // a side contact's points reach as high as the body's top face, where they tie with the contacts
  // of the bodies resting on it: un-marking the body in the sweep could come after those were
  // marked stable on its strength. Ruling it out first gives every body its final verdict before
  // anything rests on it.
  for (const ContactManifold& c : contacts) {
    if (c.count == 0 || alongY(c.normal, params)) continue;
    marks[c.a].ruledOut = true;
    marks[c.b].ruledOut = true;
  }

  // SETGEOMETRICALLYSTABLE L6: lowest contact points first, so a bottom body is judged before its
  // top body.
  sortContactPointsAscending(contacts, params, sorted_);
  const std::vector<VerticalContact>& sorted = sorted_;

  // SETGEOMETRICALLYSTABLE L7-L8: each contact point in turn.
  for (const VerticalContact& c : sorted) {
    // SETGEOMETRICALLYSTABLE L9-L11: the body judged is the top one.
    const int o = c.top;
    // DEVIATION(SETGEOMETRICALLYSTABLE L20): an immovable top body (a ceiling resting on a box)
    // keeps the verdict of L2-L3: nothing can move it, whatever is under it.
    if (world.bodies[o].immovable) continue;

    // SETGEOMETRICALLYSTABLE L12-L13: the top body's outward normal at the point points down (the
    // manifold normal is along y and the top body is the one it points away from below) and the
    // bottom body is already stable.
    // DEVIATION(SETGEOMETRICALLYSTABLE L13): the outward normal is also required to be the top
    // body's own face normal, i.e. the body is level. A tilted box resting on an edge or a corner
    // touches along the other body's face normal, yet its own outward normal there is not −y and it
    // has no bottom plane whose corners could be marked.
    if (bottom[o].level && stable[c.bottom]) {
      // SETGEOMETRICALLYSTABLE L14-L15: mark the bottom-face corners this point coincides with,
      // seen from above.
      for (int k = 0; k < 4; ++k)
        if ((c.xz - bottom[o].corners[k]).norm() <= bottom[o].tolerance)
          marks[o].corners[k] = true;
      if (params.useSupportHull) marks[o].support.push_back(c.xz);

      // SETGEOMETRICALLYSTABLE L16-L17: all four corners marked (or, as the footnote's ablation,
      // the support hull covers the bottom face) and nothing has ruled the body out.
      const bool supported =
          params.useSupportHull
              ? hullCoversFace(marks[o].support, bottom[o], hullPoints_, hull_)
              : std::all_of(marks[o].corners.begin(), marks[o].corners.end(),
                            [](bool marked) { return marked; });
      // DEVIATION(SETGEOMETRICALLYSTABLE L17): a body ruled out earlier stays out; otherwise a
      // later point at the same height could mark it stable again after L20, and the verdict would
      // depend on the order of points of equal height.
      if (supported && !marks[o].ruledOut) stable[o] = kGeometricallyStable;
    } else {
      // SETGEOMETRICALLYSTABLE L18-L20: the outward normal here points down (or, on a tilted box,
      // nowhere along y), never along +y, and the body under it is not stable: this contact can
      // push the body, so it is not stable.
      stable[o] = kUnstable;
      marks[o].ruledOut = true;
    }
  }
  if (params.underLoad) addStableUnderLoad(world, contacts, params, stable);
  return stable;
}

}  // namespace boxsim
