/// \file
/// \alg{DAMPENOBJECTS} (\thesis{§5.3}).
#include "boxsim/impulse_damped/dampen_objects.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>

#include "boxsim/impulse_damped/predicted_positions.hpp"

namespace boxsim {

namespace {
/// The axis of the box closest to ±y, as a signed world vector pointing up.
Vec3 upmostAxis(const RigidBody& body) {
  const int k = body.mostVerticalAxis();
  return body.R(1, k) < 0.0 ? Vec3(-body.R.col(k)) : Vec3(body.R.col(k));
}

/// Distance between two orientations as quaternions, blind to the sign ambiguity q ~ -q.
double quaternionDistance(const Quat& p, const Quat& q) {
  return std::min((p.coeffs() - q.coeffs()).norm(), (p.coeffs() + q.coeffs()).norm());
}
}  // namespace

bool isYAxisAligned(const RigidBody& body, double angleDeg) {
  return upmostAxis(body).y() >= std::cos(angleDeg * kPi / 180.0);
}

void tiltTowardsYAxis(RigidBody& body, double maxAngle) {
  const Vec3 up = upmostAxis(body);
  const Vec3 axis = up.cross(Vec3::UnitY());
  const double sine = axis.norm();
  if (sine < 1e-15) return;
  // The turn, min(θ, maxAngle) about axis / |axis|, θ the angle of up from y, as a quaternion
  // of its half angle. For θ itself from sin θ and cos θ by the half-angle formulas, so the
  // step needs only square roots: the C libraries' atan2, sin and cos differ in the last bit
  // now and then (docs/web.md), and the same scene must give the same bits everywhere.
  const double radius = std::sqrt(sine * sine + up.y() * up.y());
  const double cosine = up.y() / radius;
  double halfCos, halfSin;
  if (cosine >= std::cos(maxAngle)) {  // θ <= maxAngle: turn by θ, up onto y
    halfCos = std::sqrt(0.5 * (1.0 + cosine));
    halfSin = (sine / radius) / (2.0 * halfCos);
  } else {
    halfCos = std::cos(0.5 * maxAngle);
    halfSin = std::sin(0.5 * maxAngle);
  }
  const Vec3 v = (halfSin / sine) * axis;
  body.s.q = (Quat(halfCos, v.x(), v.y(), v.z()) * body.s.q).normalized();
  body.updateDerived();
}

void keepSupported(const World& world, const std::vector<ContactManifold>& contacts,
                   std::vector<char>& touched, ContactIslands& islands) {
  const int n = static_cast<int>(world.bodies.size());
  // Node n stands for every immovable body: they hold up whatever rests on them.
  islands.reset(static_cast<std::size_t>(n) + 1);
  const auto node = [&world, n](int i) {
    return world.bodies[static_cast<std::size_t>(i)].immovable ? n : i;
  };
  for (const ContactManifold& m : contacts) islands.join(node(m.a), node(m.b));
  // An immovable body's mark stays; damping leaves it alone anyway.
  for (int i = 0; i < n; ++i) {
    const std::size_t k = static_cast<std::size_t>(i);
    if (touched[k] && !world.bodies[k].immovable && !islands.together(i, n)) touched[k] = 0;
  }
}

void dampMomenta(World& world, double dt, const std::vector<char>& touched,
                 const DampingParams& params, DampingStats* stats,
                 const std::vector<SupportVerdict>& support) {
  const double u = world.gravity.norm() * dt;  // the velocity unit g Δt
  const double k1 = std::exp(-params.linearRate * dt);
  const double k2 = std::exp(-params.angularRate * dt);
  const double k3 = std::exp(-params.alignedAngularRate * dt);
  for (std::size_t i = 0; i < world.bodies.size(); ++i) {  // DAMPENOBJECTS L1
    RigidBody& o = world.bodies[i];
    // DAMPENOBJECTS L2: only bodies that had a contact interaction are damped.
    if (o.immovable || !touched[i]) continue;
    const double ell = o.halfExtents.minCoeff();
    const double pUnit = o.mass * u;                              // momentum of speed g Δt
    // Angular momentum of spin g Δt / ℓ about an axis of inertia (2/3) m ℓ² (a cube of half side ℓ).
    const double lUnit = (2.0 / 3.0) * o.mass * ell * u;
    const double rotationalBefore = o.s.L.dot(o.omega);
    // DAMPENOBJECTS L3-L5.
    // DEVIATION(DAMPENOBJECTS L3-L5, L9): the rates k1-k3 are the thesis' stand-in for friction
    // (§5.2, "friction slows things down"); a body with Coulomb friction has the real thing and
    // skips them, so that friction is not counted twice. The small-velocity tests below (L6-L21),
    // which bring bodies to rest, stay.
    const bool rates = o.friction.frictionless();
    // DEVIATION(DAMPENOBJECTS L6-L21): with the support test, the steps that bring a body to
    // rest act only on a body whose centre lies over its support (DampingParams::supportTest).
    const bool gated = params.supportTest && !support.empty();
    // DEVIATION(DAMPENOBJECTS L6-L21): a body that its Coulomb friction cannot hold is not
    // rested (markFrictionSlides).
    const bool slides = !support.empty() && support[i].slides;
    // DEVIATION(DAMPENOBJECTS L6-L21): nor one that it cannot hold with what rests on it
    // (SupportVerdict::held): a stack whose load lies beyond its lowest box's edge must tip, and
    // the rests, which see one box over its support at a time, stopped every box's first turn
    // (on a plank tilted 20° with μ = 0.5, five cubes crept 0.75 m in 4 s before they toppled,
    // four crawled 0.44 m in 8 s and never did).
    // A frictional body's hold stands in for the support test: `held` asks of the centre of its
    // whole load, the bodies pressing on it included, what `over` asks of its own centre. A box
    // of a pyramid pushed out over the edge of the row under it, held down by the rows it
    // carries, was held but not over, never rested, and kept trembling (0.1-0.2 mm a step for
    // 12 s), and with it the 19 boxes above it awake.
    const bool frictionalVerdict = !rates && !support.empty();
    const bool overSupport =
        !slides && (frictionalVerdict ? support[i].held : !gated || support[i].over);
    const bool yAxisAligned = isYAxisAligned(o, params.alignedAngleDeg) && overSupport;
    // DEVIATION(DAMPENOBJECTS L10): turning a box flat (towards y, about its centre) keeps it on
    // supporting faces that are level, but lifts it off a tilted one, or off all but the highest
    // of several whose tops are not level with each other (a pile): it then overhangs what is
    // left, tips back, and is turned flat again, for ever (measured in the clump on the ground:
    // cubes rocking in place at 0.1 m/s, one on a face tilted 0.5° creeping 1 mm/s).
    // On supports that are not level, a box is left as it lies.
    const bool turnFlat = !gated || support[i].level;
    if (rates) {
      o.s.P *= k1;
      o.s.L *= k2;
    }
    // DAMPENOBJECTS L6-L10: a box lying nearly flat is turned the last bit flat (L10); if it also
    // barely moves vertically it is resting on a face and loses its vertical velocity (L7-L9).
    // DEVIATION(DAMPENOBJECTS L7-L9): a body its Coulomb friction holds with its load over its
    // support (SupportVerdict::held) loses a small vertical velocity as an aligned one does,
    // though it lies tilted (on a slope, or on a tilted box of a heap). The passes leave each box
    // of a stack some of the g Δt of L3 (the restitution ramp of RESOLVECONTACTS L5 and the gravity
    // trick cannot settle a stack in one step), so it ends every step falling slowly; FIXCONTACT-
    // CONSTRAINTS lifts it back along the normal of a tilted support, which walks it down the
    // slope: three cubes stacked on a plank tilted 5° with μ = 0.5, which Coulomb holds, crept
    // 19 mm in 8 s and never slept, seven crept 0.28 m in 8 s with the top one reported falling at
    // 0.4 m/s. Now they stand and sleep after 0.5 s; five on a 20° plank, whose load lies beyond
    // the lowest box's downhill edge, are not held.
    // overSupport is SupportVerdict::held for a frictional body.
    const bool held = overSupport && frictionalVerdict;
    if (yAxisAligned || held) {
      if (std::abs(o.s.P.y()) < params.verticalVelocityEps * pUnit) {
        o.s.P.y() = 0.0;
        if (rates) o.s.L *= k3;
      }
      if (yAxisAligned && turnFlat) tiltTowardsYAxis(o, params.tiltRateDegPerS * kPi / 180.0 * dt);
    }
    // DAMPENOBJECTS L11-L19: component by component.
    // DEVIATION(DAMPENOBJECTS L14): the pseudocode tests ε5 twice, which would zero every component
    // the first test shrank; the second test uses its own, smaller ε6 (k5 then has an effect).
    // DEVIATION(DAMPENOBJECTS L11-L15): not the horizontal velocity of a body its support drags
    // (SupportVerdict::dragged; markFrictionSlides).
    const bool dragged = !support.empty() && support[i].dragged;
    for (int c = 0; c < 3 && overSupport; ++c) {
      if (!(dragged && c != 1)) {
        if (std::abs(o.s.P[c]) < params.linearSmallEps * pUnit) o.s.P[c] *= params.linearSmallFactor;
        if (std::abs(o.s.P[c]) < params.linearZeroEps * pUnit) o.s.P[c] = 0.0;
      }
      if (std::abs(o.s.L[c]) < params.angularSmallEps * lUnit) o.s.L[c] *= params.angularSmallFactor;
      if (std::abs(o.s.L[c]) < params.angularZeroEps * lUnit) o.s.L[c] = 0.0;
    }
    // DAMPENOBJECTS L20-L21: a small spin about y is stopped only when it is non-negative, as
    // written (spinZeroSymmetric: of either sign).
    if (overSupport && std::abs(o.s.L.y()) < params.spinZeroEps * lUnit &&
        (o.s.L.y() >= 0.0 || params.spinZeroSymmetric))
      o.s.L.y() = 0.0;
    o.updateVelocities();  // R is current: tiltTowardsYAxis updates it when it turns the body
    // DEVIATION(DAMPENOBJECTS L10, L16-L21): the rotational energy ½ Lᵀ R I⁻¹ Rᵀ L is not diagonal
    // in the world components of L, so scaling or zeroing one of them, or turning the box with L
    // held (tiltTowardsYAxis), can raise it. §5.3's rule is that damping never adds energy: where
    // these steps did, L is scaled back to the energy it had on entry.
    const double rotationalAfter = o.s.L.dot(o.omega);
    if (rotationalAfter > rotationalBefore) {
      o.s.L *= std::sqrt(rotationalBefore / rotationalAfter);
      o.updateVelocities();
    }
    if (stats) ++stats->damped;
  }
}

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
}

DampingStats dampenObjects(World& world, double dt, const std::vector<char>& touched,
                           const DampingParams& params, Integrator integrator,
                           const std::vector<SupportVerdict>& support, SavedPoses* before) {
  DampingStats stats;
  dampMomenta(world, dt, touched, params, &stats, support);
  // DAMPENOBJECTS L22: integrateObjectPositions(Δt, STANDARD_GRAVITY) with the velocities as they
  // now are. STANDARD_GRAVITY is read as gravity applied the usual way, which L3 already did to the
  // velocities; adding g Δt again, as the passes' VELOCITY_PLUS_GRAVITY does for a prediction,
  // would count the step's gravity twice in the positions.
  SavedPoses ownPoses;
  SavedPoses& old = before ? *before : ownPoses;
  integratePositions(world, dt, integrator, old);
  // DAMPENOBJECTS L23-L28: a body that would move less than ε10 and turn less than ε11 stays put.
  // DEVIATION(DAMPENOBJECTS L23): only bodies that had a contact interaction and lie with a face
  // perpendicular to gravity (§5.3's third mark of a chattering body) are snapped. A body in
  // free flight at the top of its arc moves little in one step too and must not hang there,
  // and a box just starting to tip off an edge moves little too: snapping it holds its pose,
  // the same contacts give it the same momenta, and it stays balanced on the edge for ever
  // (seen with 0.1 m cubes).
  const double step2 = world.gravity.norm() * dt * dt;  // the length unit g Δt²
  for (std::size_t i = 0; i < world.bodies.size(); ++i) {
    RigidBody& o = world.bodies[i];
    if (o.immovable || !touched[i] || !isYAxisAligned(o, params.alignedAngleDeg)) continue;
    // DEVIATION(DAMPENOBJECTS L23): with the support test, only over its support (as L6-L21).
    if (params.supportTest && !support.empty() && !support[i].over) continue;
    // DEVIATION(DAMPENOBJECTS L23): nor one its Coulomb friction cannot hold, alone or with what
    // rests on it, nor one its support drags (SupportVerdict::dragged).
    if (!support.empty() && (support[i].slides || support[i].dragged ||
                             (!o.friction.frictionless() && !support[i].held)))
      continue;
    // DEVIATION(DAMPENOBJECTS L26): the turn is measured by how far it carries the ends of the
    // body's longest axis (its largest half extent), not its thickness ℓ: a slab 1 m tall and
    // 0.1 m thick tipping at 1.4 rad/s turns by 0.011 in quaternion distance a step, within
    // ε11 g Δt² / ℓ, and was held upright, though its top moved 12 mm a step; and the body the
    // snap holds with friction loses its turn (restHeld). For a cube the two are the same length
    // (DampingParams::rotationSnapEps).
    const double reach = o.halfExtents.maxCoeff();
    const double deltaPosition = (o.s.x - old[i].x).norm();
    const double deltaRotation = quaternionDistance(o.s.q, old[i].q);
    if (deltaPosition < params.positionSnapEps * step2 &&
        deltaRotation < params.rotationSnapEps * step2 / reach) {
      // DEVIATION(DAMPENOBJECTS L26-L28): a body its friction holds (only frictional bodies
      // are ever held) and the rests left no linear momentum ends the step at rest
      // (DampingParams::restHeld); the velocities follow in restorePose.
      if (params.restHeld && !support.empty() && support[i].held && o.s.P.isZero(0.0))
        o.s.L.setZero();
      restorePose(o, old[i]);
      ++stats.snapped;
    }
  }
  return stats;
}

}  // namespace boxsim
