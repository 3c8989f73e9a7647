/// \file
/// Coulomb's cone on DAMPENOBJECTS' rests (friction_slides.hpp).
#include "boxsim/impulse_damped/friction_slides.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace boxsim {

namespace {
/// The point of the convex hull of the xz points [points, points + count) nearest to c (c itself
/// when it lies over the hull); `hull` has room for 2 count points.
Vec2 nearestInHull(Vec2* points, std::size_t count, Vec2* hull, const Vec2& c) {
  if (overHull(points, count, hull, c, 0.0)) return c;
  const std::size_t size = convexHullXZ(points, count, hull);
  if (size == 1) return hull[0];
  Vec2 nearest = hull[0];
  double best = std::numeric_limits<double>::infinity();
  // Every edge of the hull (a segment: its one edge, both ways).
  for (std::size_t k = 0; k < size; ++k) {
    const Vec2 p = nearestOnSegment(hull[k], hull[(k + 1) % size], c);
    const double d = (p - c).squaredNorm();
    if (d < best) {
      best = d;
      nearest = p;
    }
  }
  return nearest;
}

/// Whether, at some point of manifold m between `body` and the movable body `under` it rests
/// on, `under`'s surface slides along it faster than `speed` (m/s): the part of their relative
/// velocity there that lies in the contact plane.
bool slipsFaster(const RigidBody& body, const RigidBody& under, const ContactManifold& m,
                 double speed) {
  for (int k = 0; k < m.count; ++k) {
    const Vec3& p = m.points[k].position;
    const Vec3 slip = (under.v + under.omega.cross(Vec3(p - under.s.x))) -
                      (body.v + body.omega.cross(Vec3(p - body.s.x)));
    if ((slip - slip.dot(m.normal) * m.normal).squaredNorm() > speed * speed) return true;
  }
  return false;
}

/// SupportVerdict::held (markFrictionSlides) from the sums markFrictionSlides made; `down` is ĝ.
void markFrictionHeld(const World& world, const Vec3& down, std::vector<SupportVerdict>& support,
                      FrictionSlideLists& sums) {
  const std::size_t n = world.bodies.size();
  std::vector<double>& load = sums.load;
  std::vector<Vec3>& moment = sums.moment;
  load.assign(n, 0.0);
  moment.assign(n, Vec3::Zero());
  for (std::size_t i = 0; i < n; ++i) {
    const RigidBody& body = world.bodies[i];
    if (body.immovable) continue;
    load[i] = body.mass;
    moment[i] = body.mass * body.s.x;
  }
  // From the top down: a body passes its load on to the movable bodies under it, in proportion
  // to what each contact bears, once every body above it has passed it theirs.
  const auto height = [&](int i) { return -down.dot(world.bodies[i].s.x); };
  std::vector<FrictionSlideLists::Carried>& carried = sums.carried;
  std::sort(carried.begin(), carried.end(), [&](const auto& x, const auto& y) {
    const double hx = height(x.body), hy = height(y.body);
    return hx > hy || (hx == hy && (x.body < y.body || (x.body == y.body && x.under < y.under)));
  });
  const std::vector<double>& weight = sums.weight;
  std::vector<Vec2>& patch = sums.group;
  std::vector<Vec2>& patchHull = sums.hull;
  for (const FrictionSlideLists::Carried& c : carried) {
    if (!(height(c.under) < height(c.body))) continue;
    const std::size_t body = static_cast<std::size_t>(c.body);
    const double share = c.bears / weight[body] * load[body];
    // Its share presses on the under body where the contact's patch comes nearest to the
    // centre of its load, seen from above: under the centre itself for a body on one support
    // (a stack passes its whole load's centre down), at the patch's edge towards it for a body
    // bridging several (a box lying across the corner of another presses on that corner).
    const Vec3 centre = moment[body] / load[body];
    patch.assign(sums.patches.begin() + static_cast<std::ptrdiff_t>(c.first),
                 sums.patches.begin() + static_cast<std::ptrdiff_t>(c.first + c.count));
    patchHull.resize(2 * c.count);
    const Vec2 at =
        nearestInHull(patch.data(), c.count, patchHull.data(), Vec2(centre.x(), centre.z()));
    load[static_cast<std::size_t>(c.under)] += share;
    moment[static_cast<std::size_t>(c.under)] += share * Vec3(at.x(), centre.y(), at.y());
  }
  // Each body's support points together, and the load's centre over their hull.
  std::vector<std::pair<int, Vec2>>& points = sums.points;
  std::sort(points.begin(), points.end(), [](const auto& x, const auto& y) {
    return x.first < y.first ||
           (x.first == y.first && (x.second.x() < y.second.x() ||
                                   (x.second.x() == y.second.x() && x.second.y() < y.second.y())));
  });
  std::vector<Vec2>& hull = sums.hull;
  std::vector<Vec2>& own = sums.group;
  for (std::size_t k = 0; k < points.size();) {
    const int i = points[k].first;
    std::size_t end = k;
    while (end < points.size() && points[end].first == i) ++end;
    const RigidBody& body = world.bodies[static_cast<std::size_t>(i)];
    if (!body.immovable && !body.friction.frictionless() && !support[i].slides) {
      const std::size_t count = end - k;
      hull.resize(2 * count);
      own.resize(count);
      for (std::size_t j = 0; j < count; ++j) own[j] = points[k + j].second;
      const Vec3 centre = moment[static_cast<std::size_t>(i)] / load[static_cast<std::size_t>(i)];
      support[i].held =
          overHull(own.data(), count, hull.data(), Vec2(centre.x(), centre.z()), 1e-9);
    }
    k = end;
  }
  // A body whose supports that hold it bear less than half its weight is not held either: the
  // stack under it may tip. As with slides, only a supported body passes it on (a body in flight
  // has nothing to hold it). A brick lying on two, one at the edge of a hole, is held by the
  // other (the header).
  // What the supports that do not hold a body bear (movable, supported and not held): more than
  // half its weight, and the rest (immovable supports, held ones, ones in flight) bear less.
  std::vector<double>& unheldBears = sums.unheldBears;
  for (bool changed = true; changed;) {
    changed = false;
    unheldBears.assign(n, 0.0);
    for (const FrictionSlideLists::Carried& c : carried)
      if (!support[c.under].held && weight[static_cast<std::size_t>(c.under)] > 0.0)
        unheldBears[static_cast<std::size_t>(c.body)] += c.bears;
    for (const FrictionSlideLists::Carried& c : carried) {
      const std::size_t body = static_cast<std::size_t>(c.body);
      if (!support[body].held || unheldBears[body] <= 0.5 * weight[body]) continue;
      support[body].held = false;
      changed = true;
    }
  }
}

/// SupportVerdict::grounded (markFrictionSlides) from the verdicts' `held`, the bodies on an
/// immovable one and the carrying contacts of `sums`, which markFrictionHeld left sorted from
/// the top down; `down` is ĝ.
void markGrounded(const World& world, const Vec3& down, std::vector<SupportVerdict>& support,
                  const FrictionSlideLists& sums) {
  const std::size_t n = world.bodies.size();
  for (std::size_t i = 0; i < n; ++i) support[i].grounded = support[i].held && sums.onImmovable[i];
  // On a lower grounded body, from the bottom up: a body's verdict is settled before any body
  // above it reads it.
  const auto height = [&](int i) { return -down.dot(world.bodies[i].s.x); };
  for (auto c = sums.carried.rbegin(); c != sums.carried.rend(); ++c)
    if (height(c->under) < height(c->body) && support[c->under].grounded && support[c->body].held)
      support[c->body].grounded = true;
}
}  // namespace

void markFrictionSlides(const World& world, const std::vector<ContactManifold>& contacts,
                        std::vector<SupportVerdict>& support, FrictionSlideLists* lists,
                        const SupportTestParams& params, double dragSpeed) {
  const std::size_t n = world.bodies.size();
  support.resize(n, SupportVerdict{true, true, false, false, false});
  for (SupportVerdict& verdict : support)  // its own fields
    verdict.slides = verdict.held = verdict.dragged = false;
  const double g = world.gravity.norm();
  if (!(g > 0.0)) return;
  const Vec3 down = world.gravity / g;
  if (!world.hasFriction()) return;
  // Per body: the sum of the unit normals of its supports (into it), each weighted by how much
  // of gravity it can bear (its component against gravity: a side contact bears none), and
  // their μs averaged with the same weights.
  FrictionSlideLists own;
  FrictionSlideLists& sums = lists ? *lists : own;
  std::vector<Vec3>& pushed = sums.pushed;
  std::vector<double>& weight = sums.weight;
  std::vector<double>& mu = sums.mu;
  std::vector<FrictionSlideLists::Carried>& carried = sums.carried;
  std::vector<std::pair<int, Vec2>>& points = sums.points;
  pushed.assign(n, Vec3::Zero());
  sums.onImmovable.assign(n, 0);
  weight.assign(n, 0.0);
  mu.assign(n, 0.0);
  std::vector<Vec2>& patches = sums.patches;
  carried.clear();
  points.clear();
  patches.clear();
  for (std::size_t index = 0; index < contacts.size(); ++index) {
    const ContactManifold& m = contacts[index];
    if (m.count == 0) continue;
    const double muStatic =
        combinedFriction(world.bodies[m.a].friction, world.bodies[m.b].friction).muStatic;
    for (const int i : {m.a, m.b}) {
      const Vec3 into = i == m.b ? m.normal : Vec3(-m.normal);  // the normal runs from a to b
      const double bears = -into.dot(down);
      if (!(bears > 0.0)) continue;  // it does not push i against gravity
      pushed[i] += bears * into;
      weight[i] += bears;
      mu[i] += bears * muStatic;
      const int under = i == m.b ? m.a : m.b;
      // Where the two touch, seen from above: the faces' patch when both lie face to face (the
      // narrow phase may give such a pair one point, on an edge), else the manifold's points.
      const std::size_t first = patches.size();
      const SupportTest::Polygon patch =
          levelContactPatch(world.bodies[i], world.bodies[under], params);
      if (patch.count > 0)
        patches.insert(patches.end(), patch.points.begin(), patch.points.begin() + patch.count);
      else
        for (int k = 0; k < m.count; ++k)
          patches.emplace_back(m.points[k].position.x(), m.points[k].position.z());
      const std::size_t count = patches.size() - first;
      for (std::size_t k = first; k < patches.size(); ++k) points.emplace_back(i, patches[k]);
      if (!world.bodies[i].immovable && world.bodies[under].immovable) sums.onImmovable[i] = 1;
      if (!world.bodies[i].immovable && !world.bodies[under].immovable) {
        carried.push_back({i, under, bears, first, count});
        // Its support slips under it faster than the rests reach: their friction drags it.
        if (!world.bodies[i].friction.frictionless() && muStatic > 0.0 &&
            slipsFaster(world.bodies[i], world.bodies[under], m, dragSpeed))
          support[i].dragged = true;
      }
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    const RigidBody& body = world.bodies[i];
    if (body.immovable || body.friction.frictionless()) continue;
    const double length = pushed[i].norm();
    // No support, or only frictionless ones, which hold nothing along them.
    if (!(length > 0.0) || !(mu[i] > 0.0)) {
      support[i].slides = true;
      continue;
    }
    const Vec3 N = pushed[i] / length;
    const double into = -down.dot(N);               // gravity's part into the supports
    const double along = (down + into * N).norm();  // and along their plane
    support[i].slides = along > (mu[i] / weight[i]) * into;
  }
  // A body that rests on one that slides is not held where it lies either: its rests would keep
  // it still while its support moves away under it, and its friction would then hold the support
  // back (two flat boxes on a plank tilted 30°, μ 0.8 between them and 0.5 on the plank, stood
  // still where Coulomb slides both at 0.66 m/s²). Marked up the supports until none changes.
  // Only a supported body that slides passes it on: one in flight carries what lies on it along,
  // and marking that too left boxes of the clump on the ground unrested as they met in the air
  // (with μ = 0.5 the heap then never slept whole; 2.83 s without).
  for (bool changed = true; changed;) {
    changed = false;
    for (const FrictionSlideLists::Carried& c : carried) {
      if (support[c.body].slides || !support[c.under].slides || !(weight[c.under] > 0.0) ||
          world.bodies[c.body].friction.frictionless())
        continue;
      support[c.body].slides = true;
      changed = true;
    }
  }
  markFrictionHeld(world, down, support, sums);
  markGrounded(world, down, support, sums);
}

}  // namespace boxsim
