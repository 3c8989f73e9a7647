/// \file
/// The modified timewarp, \alg{A.1}; each step below is tagged with its pseudocode line.
#include "boxsim/timewarp/timewarp.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <set>
#include <stdexcept>
#include <tuple>

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/collision/contact_manifold.hpp"
#include "boxsim/collision/separating_axis.hpp"
#include "boxsim/core/newtonian_impulse.hpp"
#include "boxsim/impulse_damped/fix_contact_constraints.hpp"

namespace boxsim {

std::string timewarpMethodName(TimewarpVariant variant) {
  return enumName(kTimewarpMethodNames, variant);
}

namespace {

/// A pending collision of the heap: its time (s after the frame's start: the first instant
/// found touching) and its pair, a < b, and the last instant found apart (`before` <= time).
/// Ordered by time, then pair, so equal times resolve in a fixed order (determinism).
struct PendingCollision {
  double time = 0.0;
  int a = -1;
  int b = -1;
  double before = 0.0;
  bool operator<(const PendingCollision& o) const {
    return std::tie(time, a, b) < std::tie(o.time, o.a, o.b);
  }
};

/// Axis-aligned bounds of a box, m.
struct Bounds {
  Vec3 low, high;
  bool overlaps(const Bounds& o) const {
    return (low.array() <= o.high.array()).all() && (o.low.array() <= high.array()).all();
  }
  Bounds merged(const Bounds& o) const { return {low.cwiseMin(o.low), high.cwiseMax(o.high)}; }
  Bounds widened(double m) const { return {low.array() - m, high.array() + m}; }
};

Bounds boundsOf(const RigidBody& body) {
  const Vec3 reach = body.R.cwiseAbs() * body.halfExtents;
  return {body.s.x - reach, body.s.x + reach};
}

/// The two states of \alg{A.1} per body, the valid times, the collision heap and the counters
/// of one frame.
class Frame {
 public:
  Frame(World& world, double dt, const TimewarpParams& params)
      : world_(world), params_(params), end_(dt), valid_(world.bodies), test_(world.bodies),
        validTime_(world.bodies.size(), 0.0) {}

  StepStats run(std::vector<TimewarpEvent>& events);

 private:
  /// Body k's state at time t >= validTime_[k], integrated from its valid state (counted).
  RigidBody stateAt(int k, double t) {
    RigidBody body = valid_[k];
    if (!body.immovable && t > validTime_[k]) {
      integrateBody(body, t - validTime_[k], world_.gravity, params_.integrator);
      ++stats_.bodyIntegrations;
    }
    return body;
  }

  double depth(const RigidBody& a, const RigidBody& b) const {
    return separatingAxisTest(Obb::of(a), Obb::of(b)).depth;
  }

  /// The pair's manifold for an impulse: points closer than the swept variant's gap, so a
  /// pair it stopped just apart still has a contact, and corners farther off are no part of it.
  ContactManifold impulseManifold(const RigidBody& a, const RigidBody& b) const {
    return collideBoxes(Obb::of(a), Obb::of(b), params_.sweptGap);
  }

  bool approaching(const RigidBody& a, const RigidBody& b) const {
    const ContactManifold m = impulseManifold(a, b);
    if (m.count == 0) return false;
    return relativeNormalVelocity(a, b, m.centroid(), m.normal) < 0.0;
  }

  bool bothImmovable(int a, int b) const {
    return world_.bodies[a].immovable && world_.bodies[b].immovable;
  }

  /// The collision time of pair (a, b), which intersects at `hi`, by bisection over
  /// [max(validTime_a, validTime_b), hi] within `resolution`; nothing when the pair already
  /// intersects at the start of the bracket without approaching (a resting contact, which
  /// FIXINTERPENETRATION handles, not an event).
  std::optional<PendingCollision> bisect(int a, int b, double hi) {
    double lo = std::max(validTime_[a], validTime_[b]);
    const RigidBody startA = stateAt(a, lo), startB = stateAt(b, lo);
    if (depth(startA, startB) > params_.depthTolerance) {
      if (!approaching(startA, startB)) return std::nullopt;
      return PendingCollision{lo, a, b, lo};
    }
    while (hi - lo > params_.resolution) {
      const double mid = 0.5 * (lo + hi);
      if (mid <= lo || mid >= hi) break;
      ++stats_.bisections;
      if (depth(stateAt(a, mid), stateAt(b, mid)) > params_.depthTolerance)
        hi = mid;
      else
        lo = mid;
    }
    return PendingCollision{hi, a, b, lo};
  }

  /// The swept variant's test of pair (a, b) over [max(validTimes), end]: conservative
  /// advancement. The separating-axis gap (−depth) never exceeds the boxes' distance, and the
  /// gap closes no faster than closingSpeedBound, so advancing by gap / that bound never passes
  /// a contact.
  std::optional<PendingCollision> sweep(int a, int b) {
    double t = std::max(validTime_[a], validTime_[b]);
    const double speed = closingSpeedBound(a, b);
    for (int iteration = 0; iteration < 1000 && t <= end_; ++iteration) {
      const RigidBody sa = stateAt(a, t), sb = stateAt(b, t);
      const double d = depth(sa, sb);
      if (speed <= 0.0) return std::nullopt;
      if (d > -params_.sweptGap) {
        if (approaching(sa, sb)) return PendingCollision{t, a, b, t};
        // Within the gap but not approaching (just after a collision of this pair, or
        // resting): step past the gap band. No point closes it faster than `speed`, so this
        // overshoots a contact by at most sweptGap.
        t += std::max(params_.resolution, (params_.sweptGap - d) / speed);
        continue;
      }
      t += -d / speed;
    }
    // Out of iterations (a fast body sliding slowly closer: the bound counts its whole speed),
    // or past the frame: the test states decide, with bisection, as in the simple variant.
    if (depth(test_[a], test_[b]) > params_.depthTolerance) return bisect(a, b, end_);
    return std::nullopt;
  }

  /// m/s: a bound on how fast any point of a approaches any point of b over the rest of the
  /// frame. stateAt moves a body from its valid time t_k in one step, its centre along
  /// x_k + v_k τ + c g τ² (τ = t − t_k; c = 0, ½ or 1 by the integrator), so the centres'
  /// relative velocity is v_b − v_a + 2 c g (t_a − t_b): the fall both bodies share cancels,
  /// and a pair resting together, which moves as one, gets a bound near zero instead of the
  /// 2 g Δ of two falls. Against an immovable body it is |v| + 2 g Δ. Turning adds
  /// |ω|max |h| for each movable body (|ω| = |I⁻¹ L| <= |L| / I_min, |L| constant in flight).
  double closingSpeedBound(int a, int b) const {
    const RigidBody& A = valid_[a];
    const RigidBody& B = valid_[b];
    const double g = world_.gravity.norm();
    const auto turning = [](const RigidBody& body) {
      return body.immovable ? 0.0
                            : body.s.L.norm() * body.IbodyInvDiag.maxCoeff() * body.halfExtents.norm();
    };
    double linear = 0.0;
    if (A.immovable || B.immovable) {
      const int k = A.immovable ? b : a;
      linear = valid_[k].v.norm() + 2.0 * g * (end_ - validTime_[k]);
    } else {
      linear = (B.v - A.v).norm() + 2.0 * g * std::abs(validTime_[a] - validTime_[b]);
    }
    return linear + turning(A) + turning(B);
  }

  /// The collision of pair (a, b) after the bodies' valid times, if any: the swept test, or
  /// (simple and safer) bisection when the test states intersect.
  std::optional<PendingCollision> collisionOf(int a, int b) {
    if (a > b) std::swap(a, b);
    if (bothImmovable(a, b)) return std::nullopt;
    if (params_.variant == TimewarpVariant::Swept) {
      if (!sweptBounds(a).overlaps(sweptBounds(b))) return std::nullopt;
      return sweep(a, b);
    }
    if (!boundsOf(test_[a]).overlaps(boundsOf(test_[b]))) return std::nullopt;
    if (depth(test_[a], test_[b]) <= params_.depthTolerance) return std::nullopt;
    return bisect(a, b, end_);
  }

  /// Bounds of body k over the rest of the frame: its valid and test poses, widened by how far
  /// a corner may stray from the straight path (rotation, gravity's bend).
  Bounds sweptBounds(int k) const {
    const Bounds both = boundsOf(valid_[k]).merged(boundsOf(test_[k]));
    if (valid_[k].immovable) return both;
    const double span = end_ - validTime_[k];
    return both.widened(0.5 * world_.gravity.norm() * span * span + valid_[k].halfExtents.norm());
  }

  /// SIMPLESYNCTIMEWARP L5, SAFERSYNCTIMEWARP L5: findAllCollisions, the pairs whose bounds (test
  /// states, or swept bounds) overlap, found by the world's broad phase over those bounds
  /// (candidatePairs: sweep and prune or all pairs, the same pairs in the same order), then each
  /// pair's collision.
  void findAllCollisions() {
    const int n = static_cast<int>(world_.bodies.size());
    std::vector<Vec3> lo(n), hi(n);
    for (int k = 0; k < n; ++k) {
      const Bounds b =
          params_.variant == TimewarpVariant::Swept ? sweptBounds(k) : boundsOf(test_[k]);
      lo[k] = b.low;
      hi[k] = b.high;
    }
    // boundsWithin with margin 0 is Bounds::overlaps; the pairs of two immovable bodies it
    // leaves out have no collision (collisionOf).
    for (const auto& [a, b] : candidatePairs(world_, lo, hi, 0.0))
      if (const auto c = collisionOf(a, b)) heap_.insert(*c);
  }

  /// SIMPLESYNCTIMEWARP L18, SAFERSYNCTIMEWARP L29: addCollisionsForObject.
  void addCollisionsForObject(int k) {
    for (int j = 0; j < static_cast<int>(world_.bodies.size()); ++j)
      if (j != k)
        if (const auto c = collisionOf(k, j)) heap_.insert(*c);
  }

  /// SIMPLESYNCTIMEWARP L10, SAFERSYNCTIMEWARP L20: removeCollisionsForObject.
  void removeCollisionsForObject(int k) {
    for (auto it = heap_.begin(); it != heap_.end();)
      it = (it->a == k || it->b == k) ? heap_.erase(it) : std::next(it);
  }

  /// SIMPLESYNCTIMEWARP L13, SAFERSYNCTIMEWARP L24: collideTwoObjects, the Newtonian impulse at the
  /// centroid of the pair's contact `m`, applied to a and b; true when it changed their velocities.
  bool collideTwoObjects(RigidBody& a, RigidBody& b, const ContactManifold& m) {
    if (m.count == 0) return false;
    return applyNewtonianImpulse(a, b, m.centroid(), m.normal, world_.restitution) > 0.0;
  }

  /// SIMPLESYNCTIMEWARP L8-L18, SAFERSYNCTIMEWARP L17-L29: resolve collision c, both bodies
  /// rewound to c.time, and look for their next collisions.
  ///
  /// DEVIATION(SIMPLESYNCTIMEWARP L11-L13, SAFERSYNCTIMEWARP L22-L24): the contact is taken where
  /// the pair first touches (c.time), the impulse is applied to the bodies where they were last
  /// apart (c.before, within `resolution`), and that becomes their valid time, as the basic
  /// technique does. Made valid at c.time, overlapping, the pair would look resting there and a
  /// second collision of the same pair in the frame would be lost.
  void resolve(const PendingCollision& c, std::vector<TimewarpEvent>& events) {
    const ContactManifold m = impulseManifold(stateAt(c.a, c.time), stateAt(c.b, c.time));
    for (const int index : {c.a, c.b}) {
      // SIMPLESYNCTIMEWARP L10-L12, SAFERSYNCTIMEWARP L20, L22-L23.
      removeCollisionsForObject(index);
      valid_[index] = stateAt(index, c.before);
      validTime_[index] = std::max(validTime_[index], c.before);
    }
    // SIMPLESYNCTIMEWARP L13, SAFERSYNCTIMEWARP L24.
    collideTwoObjects(valid_[c.a], valid_[c.b], m);
    events.push_back(TimewarpEvent{c.time, c.a, c.b});
    ++stats_.events;
    for (const int index : {c.a, c.b}) {
      test_[index] = stateAt(index, end_);  // SIMPLESYNCTIMEWARP L16-L17, SAFERSYNCTIMEWARP L27-L28
      ++stats_.bodyRollbacks;
    }
    // SIMPLESYNCTIMEWARP L18, SAFERSYNCTIMEWARP L29.
    for (const int index : {c.a, c.b}) addCollisionsForObject(index);
  }

  /// SAFERSYNCTIMEWARP L8: findNearObjects, the pair and every body whose test-state bounds,
  /// widened by nearMargin, overlap the pair's.
  std::vector<int> findNearObjects(const PendingCollision& c) const {
    const Bounds pair = boundsOf(test_[c.a]).merged(boundsOf(test_[c.b])).widened(params_.nearMargin);
    std::vector<int> near{c.a, c.b};
    for (int k = 0; k < static_cast<int>(world_.bodies.size()); ++k)
      if (k != c.a && k != c.b && boundsOf(test_[k]).overlaps(pair)) near.push_back(k);
    return near;
  }

  World& world_;
  const TimewarpParams& params_;
  const double end_;
  std::vector<RigidBody> valid_, test_;
  std::vector<double> validTime_;
  std::set<PendingCollision> heap_;
  StepStats stats_;
};

StepStats Frame::run(std::vector<TimewarpEvent>& events) {
  const int n = static_cast<int>(world_.bodies.size());
  // SIMPLESYNCTIMEWARP L1-L4, SAFERSYNCTIMEWARP L1-L4: every test state is its valid state
  // integrated over the whole frame.
  for (int i = 0; i < n; ++i) test_[i] = stateAt(i, end_);
  findAllCollisions();      // SIMPLESYNCTIMEWARP L5, SAFERSYNCTIMEWARP L5
  while (!heap_.empty()) {  // SIMPLESYNCTIMEWARP L6, SAFERSYNCTIMEWARP L6
    if (stats_.events >= params_.maxEventsPerStep) {
      stats_.limitReached = true;
      break;
    }
    // SIMPLESYNCTIMEWARP L7, SAFERSYNCTIMEWARP L7.
    const PendingCollision cur = *heap_.begin();
    heap_.erase(heap_.begin());
    if (params_.variant == TimewarpVariant::Safer) {
      // SAFERSYNCTIMEWARP L8-L13: the bodies near the collision, at its time, checked for an
      // earlier collision among themselves.
      // DEVIATION(SAFERSYNCTIMEWARP L11-L12, L19, L21-L23): the pseudocode overwrites the near
      // bodies' test states with their states at the collision time and never integrates them to
      // the end of the frame again, which L30-L31 would then make valid; and L22-L23 reuse `index`
      // from the loop before. The states at the collision time are temporaries here, and the near
      // bodies keep their test states, so L19, which takes the pair out of the bodies L21-L23
      // move, has nothing to do.
      const std::vector<int> near = findNearObjects(cur);
      std::vector<RigidBody> probe;
      for (const int k : near) probe.push_back(stateAt(k, cur.time));
      std::optional<PendingCollision> earliest;
      for (std::size_t p = 0; p < near.size(); ++p)
        for (std::size_t q = p + 1; q < near.size(); ++q) {
          const int a = std::min(near[p], near[q]), b = std::max(near[p], near[q]);
          if ((a == cur.a && b == cur.b) || bothImmovable(a, b)) continue;
          if (depth(probe[p], probe[q]) <= params_.depthTolerance) continue;
          const auto c = bisect(a, b, cur.time);  // SAFERSYNCTIMEWARP L13: findCollisionsForGroup
          if (c && c->time < cur.time && (!earliest || *c < *earliest)) earliest = c;
        }
      if (earliest) {
        // SAFERSYNCTIMEWARP L14-L15: the earlier collision goes into the heap and is resolved
        // first.
        // DEVIATION(SAFERSYNCTIMEWARP L15): the current collision goes back in too; dropped, it
        // would be lost whenever the earlier one involves other bodies.
        heap_.insert(*earliest);
        heap_.insert(cur);
        continue;
      }
    }
    resolve(cur, events);  // SIMPLESYNCTIMEWARP L8-L18, SAFERSYNCTIMEWARP L16-L29
  }
  // Past the event limit, every body stops at the last instant found apart before the earliest
  // collision left in the heap (or at its valid time, if later), and the rest of the frame is
  // dropped, as the basic colliding technique keeps its last collision-free state
  // (BasicCollidingParams::maxEventsPerStep). Test states would carry the bodies of the dropped
  // collisions on through the bodies they meet: a resting pile, whose contacts are collisions
  // again every frame, then sank through the ground faster than FIXINTERPENETRATION lifts it
  // (random stress scenes, bench/stress_bench.cpp). Stopping only those bodies is not enough: a
  // body falling onto a stopped one goes on into it.
  if (stats_.limitReached && !heap_.empty()) {
    const double stop = heap_.begin()->before;
    for (int k = 0; k < n; ++k)
      if (!valid_[k].immovable) test_[k] = stateAt(k, std::max(validTime_[k], stop));
  }
  // SIMPLESYNCTIMEWARP L19-L21, SAFERSYNCTIMEWARP L30-L32: every body's test state becomes valid at
  // the end of the frame.
  for (int i = 0; i < n; ++i) {
    world_.bodies[i].s = test_[i].s;
    world_.bodies[i].updateDerived();
  }
  return stats_;
}

}  // namespace

TimewarpStepper::TimewarpStepper(const TimewarpParams& params) : params_(params) {
  if (!(params.resolution > 0.0) || !std::isfinite(params.resolution))
    throw std::invalid_argument("timewarp: resolution must be a finite number of seconds > 0");
  if (!(params.depthTolerance >= 0.0) || !(params.sweptGap > 0.0) || !(params.nearMargin >= 0.0) ||
      !(params.contactMargin >= 0.0) || !std::isfinite(params.sweptGap + params.nearMargin))
    throw std::invalid_argument(
        "timewarp: depthTolerance, nearMargin and contactMargin must be finite numbers >= 0, "
        "sweptGap > 0 (m)");
  if (params.maxEventsPerStep < 1)
    throw std::invalid_argument("timewarp: maxEventsPerStep must be at least 1");
}

std::map<std::string, std::string> TimewarpStepper::parameters() const {
  return {{"integrator", integratorName(params_.integrator)},
          {"resolution_s", shortestText(params_.resolution)},
          {"depth_tolerance_m", shortestText(params_.depthTolerance)},
          {"swept_gap_m", shortestText(params_.sweptGap)},
          {"near_margin_m", shortestText(params_.nearMargin)},
          {"max_events_per_step", std::to_string(params_.maxEventsPerStep)},
          {"fix_interpenetration", params_.fixInterpenetration ? "on" : "off"}};
}

std::string TimewarpStepper::workLimit() const {
  return "at most " + std::to_string(params_.maxEventsPerStep) +
         " collisions a frame (max_events_per_step); collisions crowding together as bodies "
         "come to rest reach it (thesis §4.3)";
}

StepStats TimewarpStepper::step(World& world, double dt) {
  events_.clear();
  Frame frame(world, dt, params_);
  StepStats stats = frame.run(events_);
  if (params_.fixInterpenetration)
    // SIMPLESYNCTIMEWARP L22, SAFERSYNCTIMEWARP L33: fixInterpenetration.
    fixContactConstraints(world, params_.contactMargin, params_.fix, dt);
  stats.contacts = static_cast<int>(findContacts(world, params_.contactMargin).size());
  return stats;
}

}  // namespace boxsim
