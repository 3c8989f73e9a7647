/// \file
/// The slow-pair prediction of the once-per-step gathering.
#include "boxsim/impulse_damped/slow_pair_cache.hpp"

#include <algorithm>
#include <cmath>

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/collision/contact_manifold.hpp"
#include "boxsim/collision/obb.hpp"
#include "boxsim/collision/separating_axis.hpp"

namespace boxsim {

void SlowPairCache::clear() {
  pairs_.clear();
  reaches_.clear();
  predicted_.clear();
  points_.clear();
  exactManifolds_.clear();
  alternates_.clear();
}

bool SlowPairCache::wanted(const World& world, const StepBodies& bodies, int i, int j,
                           double margin, double slowWidening, double& pairMargin) const {
  // Gathered as written, pass by pass, unless the two move together.
  const bool together = pairReach_ && bodies.movingTogether(i, j);
  if ((bodies.fast[i] || bodies.fast[j]) && !together) return false;
  const RigidBody& bodyI = world.bodies[i];
  const RigidBody& bodyJ = world.bodies[j];
  // A body anchored at its predicted pose is fast again once a pass' prediction leaves it by
  // its slow bar: widened by that bar, the pair holds every point that can come within the
  // margin while both stay slow.
  const auto widening = [&](int k, const RigidBody& body) {
    if (body.immovable) return 0.0;
    if (bodies.anchored && bodies.anchorMoved[k]) return bodies.slowReach[k];
    return slowWidening * body.halfExtents.minCoeff();
  };
  const double wideningI = widening(i, bodyI);
  const double wideningJ = widening(j, bodyJ);
  // The bounds obbBounds gives, from the reach the step's bodies keep.
  Vec3 loI, hiI, loJ, hiJ;
  // With a predicted anchor `world` stands at it, and the half widths, taken at the current
  // orientations, are widened by how far the anchor's turn moves a point (anchorSlack, 0
  // without).
  boundsAbout(bodyI.s.x, bodies.reach[i], wideningI + bodies.anchorSlack[i], loI, hiI);
  boundsAbout(bodyJ.s.x, bodies.reach[j], wideningJ + bodies.anchorSlack[j], loJ, hiJ);
  if (!boundsWithin(loI, hiI, loJ, hiJ, margin)) return false;
  pairMargin = margin + wideningI + wideningJ;
  return true;
}

int SlowPairCache::add(const World& world, const StepBodies& bodies, int i, int j,
                       double pairMargin, const ContactManifold& manifold,
                       ContactNormalTracker& normals) {
  // Closer than the margin along every axis, yet no point: boxes passing corner by corner.
  // The pair stays, with no points, and gets the exact narrow phase every pass.
  if (manifold.depth <= -pairMargin) return -1;
  // A pair with a fast body is predicted from its points only: with none, it is gathered
  // as written.
  if ((bodies.fast[i] || bodies.fast[j]) && manifold.count == 0) return -1;
  // The manifold, kept with the pair (written there once, not copied about).
  CachedPair& pair = pairs_.emplace_back();
  pair.manifold = manifold;
  ContactManifold& m = pair.manifold;
  m.a = i;
  m.b = j;
  // The normal model's choice now; its face is remembered only in the passes the pair touches.
  const ImpulseContact found = normals.contactOf(world, m, false);
  PairReach& reach = reaches_.emplace_back();
  PredictedPair& predicted = predicted_.emplace_back();
  keepPoints(world, m, i, j, found, predicted, reach);
  if (edgeCorners_ && m.kind == AxisKind::EdgeEdge && m.count > 0)
    addAlternate(world, predicted, i, j, pairMargin);
  return static_cast<int>(pairs_.size()) - 1;
}

void SlowPairCache::keepPoints(const World& world, const ContactManifold& m, int i, int j,
                               const ImpulseContact& found, PredictedPair& predicted,
                               PairReach& reach) {
  const Vec3& xa = world.bodies[i].s.x;
  const Vec3& xb = world.bodies[j].s.x;
  reach = PairReach{i, j, m.count};
  predicted.normal = m.normal;
  predicted.contactNormal = found.normal;
  predicted.friction = found.friction;
  predicted.patchRadius = found.patch.radius;
  predicted.patchCount = static_cast<std::int8_t>(found.patch.count);
  for (int f = 0; f < found.patch.count; ++f)
    predicted.patchOrder[f] = static_cast<std::int8_t>(found.patch.pointOf[f]);
  predicted.first = static_cast<int>(points_.size());
  for (int k = 0; k < m.count; ++k) {
    const ContactPoint& p = m.points[k];
    const Vec3 ra = p.position - xa, rb = p.position - xb;
    points_.push_back(CachedPoint{p.position, p.depth, ra});
    reach.deepest = k == 0 ? p.depth : std::max(reach.deepest, p.depth);
    reach.leverA = std::max(reach.leverA, ra.norm());
    reach.leverB = std::max(reach.leverB, rb.norm());
  }
}

void SlowPairCache::addAlternate(const World& world, PredictedPair& pair, int i, int j,
                                 double pairMargin) {
  // At most one a pair: kept as long as the pairs' list, so that it grows only when that does.
  if (alternates_.size() == alternates_.capacity()) alternates_.reserve(pairs_.capacity());
  pair.alternate = static_cast<int>(alternates_.size());
  Alternate& alternate = alternates_.emplace_back();
  alternate.face = bestFaceAxis(Obb::of(world.bodies[i]), Obb::of(world.bodies[j]));
  alternate.clipMargin = pairMargin;
  // Nearly flush (the edge axis within about 8° of the face's normal): the corners first.
  alternate.first = std::abs(alternate.face.normal.dot(pair.normal)) > kFlushCosine;
}

void SlowPairCache::buildAlternate(const World& world, std::size_t k, Alternate& alternate,
                                   ContactNormalTracker& normals) {
  const int i = reaches_[k].a, j = reaches_[k].b;
  const Obb a = Obb::of(world.bodies[i]), b = Obb::of(world.bodies[j]);
  ContactManifold& face = alternate.manifold;
  face = manifoldWithin(clipContact(a, b, alternate.face), alternate.clipMargin);
  face.a = i;
  face.b = j;
  keepPoints(world, face, i, j, normals.contactOf(world, face, false), alternate.predicted,
             alternate.reach);
  alternate.built = true;
}

bool SlowPairCache::alternateContact(const World& world, const StepBodies& bodies, std::size_t k,
                                     double dt, double margin, ContactNormalTracker& normals,
                                     ImpulseContact& contact) {
  Alternate& alternate = alternates_[static_cast<std::size_t>(predicted_[k].alternate)];
  // Boxes apart along the edge axis by s are apart by s everywhere, and a corner of the clip,
  // which lies within the reference face's outline, is as far from the other box as from its
  // face's plane: no corner is deeper than the edge point. A pass moves a point of a body by at
  // most what mayTouch allows for its lever, and a corner (midway between the incident face and
  // the reference face's plane, within the clip's margin) lies within the body's half diagonal
  // plus that margin of either centre: when the edge point could not come within the margin
  // with such levers, no corner can.
  if (!alternate.built || alternate.reach.count > 0) {
    PairReach bound = reaches_[k];
    bound.leverA = bodies.halfDiagonal[static_cast<std::size_t>(bound.a)] + alternate.clipMargin;
    bound.leverB = bodies.halfDiagonal[static_cast<std::size_t>(bound.b)] + alternate.clipMargin;
    if (!mayTouch(bodies, bound, margin)) return false;
  }
  if (!alternate.built) buildAlternate(world, k, alternate, normals);
  if (alternate.reach.count == 0) return false;
  if (!mayTouch(bodies, alternate.reach, margin) ||
      !predictedContact(world, bodies, alternate.predicted, alternate.reach, dt, margin, contact))
    return false;
  if (!alternate.predicted.remembered) normals.remember(world, alternate.manifold);
  alternate.predicted.remembered = true;
  return true;
}

bool SlowPairCache::mayTouch(const StepBodies& bodies, const PairReach& reach, double margin) {
  const double dt = bodies.passDt;
  // A point's depth changes in the pass by n · (d_a - d_b) (predictedContact), at most
  // Δt |v'_a - v'_b| + Δt |ω| |r| + Δt² |ω|² |r| for each body; the allowance relative to the
  // terms, far above their rounding, keeps the answer what the computed depths would give.
  // The answer is true whenever deepest + Δt |v'_a - v'_b| + spin comes within the margin, up to
  // an allowance of 1e-9 of the terms (far above their rounding): the linear part is compared in
  // squares, without the square root of its norm, and may answer true a little more often than
  // the depths would, never less.
  const double wa = bodies.passSpin[reach.a], wb = bodies.passSpin[reach.b];
  const double spin = dt * (wa * reach.leverA + wb * reach.leverB) +
                      dt * dt * (wa * wa * reach.leverA + wb * wb * reach.leverB);
  const double need = -margin - reach.deepest - spin;  // what the linear part must cover
  const double allowance = 1e-9 * (std::abs(reach.deepest) + margin + spin);
  if (need <= allowance) return true;
  const double linear = need - allowance;
  return dt * dt * (bodies.passVelocity[reach.a] - bodies.passVelocity[reach.b]).squaredNorm() >
         linear * linear;
}

bool SlowPairCache::predictedContact(const World& world, const StepBodies& bodies,
                                     const PredictedPair& pair, const PairReach& reach, double dt,
                                     double margin, ImpulseContact& contact) const {
  const CachedPoint* points = points_.data() + pair.first;
  const RigidBody& a = world.bodies[reach.a];
  const RigidBody& b = world.bodies[reach.b];
  // The pass' v' and ω (StepBodies::setPass; less the anchor's with a predicted anchor, where
  // `world` then stands).
  const Vec3& ua = bodies.passVelocity[reach.a];
  const Vec3& ub = bodies.passVelocity[reach.b];
  const Vec3& wa = bodies.passOmega[reach.a];
  const Vec3& wb = bodies.passOmega[reach.b];
  const Vec3& n = pair.normal;
  const double linear = n.dot(ua - ub);
  // depth' = depth + n · (d_a - d_b) with d = Δt (u + ω × r) + ½ Δt² ω × (ω × r), where
  // n · (ω × r) = r · (n × ω) and n · (ω × (ω × r)) = (n · ω)(ω · r) - |ω|² (n · r): linear in r.
  // With r_b = r_a + e, e = x_a - x_b, the whole change is K + g · r_a, g and K the pair's:
  //   g = Δt (n × ω_a - n × ω_b) + ½ Δt² ((n · ω_a) ω_a - |ω_a|² n - (n · ω_b) ω_b + |ω_b|² n),
  //   K = Δt (n · (u_a - u_b) - e · (n × ω_b)) + ½ Δt² (|ω_b|² (n · e) - (n · ω_b)(ω_b · e)).
  // One dot product a point instead of four.
  const double nwa = n.dot(wa), nwb = n.dot(wb);
  const double wa2 = wa.squaredNorm(), wb2 = wb.squaredNorm();
  const double half = 0.5 * dt * dt;
  const Vec3 nxwb = n.cross(wb);
  const Vec3 e = a.s.x - b.s.x;
  const Vec3 g = dt * (n.cross(wa) - nxwb) +
                 half * (nwa * wa - wa2 * n - nwb * wb + wb2 * n);
  const double K = dt * (linear - e.dot(nxwb)) + half * (wb2 * n.dot(e) - nwb * wb.dot(e));
  Vec3 sum = Vec3::Zero();
  int kept = 0;
  std::array<bool, 4> keptPoint{};
  double deepest = 0.0;
  for (int i = 0; i < reach.count; ++i) {
    const CachedPoint& p = points[i];
    const double depth = p.depth + (K + g.dot(p.ra));
    if (depth <= -margin) continue;
    keptPoint[i] = true;
    deepest = kept == 0 ? depth : std::max(deepest, depth);
    sum += p.position;
    ++kept;
  }
  if (kept == 0) return false;
  // The cached contact's bodies, normal and friction; the rest is this pass' (a frictionless
  // contact's patch stays empty, its offsets unread).
  contact.a = reach.a;
  contact.b = reach.b;
  contact.normal = pair.contactNormal;
  contact.friction = pair.friction;
  contact.patch.count = 0;
  contact.patch.radius = pair.patchRadius;
  contact.point = sum / static_cast<double>(kept);
  if (!contact.friction.frictionless()) {
    // The friction patch is the kept points, about the new centroid, in the order around the
    // patch that the found contact gave them (a subset of a convex outline stays one).
    contact.patch.count = 0;
    for (int f = 0; f < pair.patchCount; ++f) {
      const int i = pair.patchOrder[f];
      if (!keptPoint[i]) continue;
      contact.patch.offsets[contact.patch.count] = points[i].position - contact.point;
      contact.patch.pointOf[contact.patch.count++] = i;
    }
  }
  contact.depth = deepest;
  contact.ra = contact.point - a.s.x;
  contact.rb = contact.point - b.s.x;
  return true;
}

}  // namespace boxsim
