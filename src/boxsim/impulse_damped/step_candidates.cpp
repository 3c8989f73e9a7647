/// \file
/// The step's candidate pairs of the once-per-step gathering (contact_gathering.hpp): every
/// body's bounds stretched along its way in a pass, one sweep over them per step, the bodies
/// that outgrow their bounds in a pass tested again, and the pairs FIXCONTACTCONSTRAINTS
/// (\alg{A.2 L5}) takes from the sweep. Only speed depends on the constants here: every pair a
/// pass looks at still passes the broad phase's own test at that pass' poses.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/impulse_damped/contact_gathering.hpp"

namespace boxsim {

namespace {
/// A body's bounds in the step's sweep are stretched this many times its displacement in a
/// pass along that displacement, so its velocity may grow this much along its way under the
/// impulses of the step before its pairs are looked for again.
constexpr double kGuardFactor = 1.5;
/// ... and grown on every side by this fraction of that displacement (and kGuardFactor times
/// what its spin can move a corner), for a velocity that turns.
/// Only speed depends on the two: a smaller guard gives fewer candidates and a cheaper sweep,
/// and more bodies that outgrow it and are tested again. On the clump of Fig. 6.7 (1000 cubes,
/// callgrind) 1.5 and 0.5 took 6 % fewer instructions than 2 and 1, and fewer than 1.5 and 0.25
/// or 1.25 and 0.25.
constexpr double kGuardSideways = 0.5;
/// Relative slack for rounding (obbBounds at two poses round differently, by a few ulp of the
/// coordinates), times the size of the coordinates plus one metre.
constexpr double kGuardRoundingSlack = 1e-9;

/// Up to this many bodies outgrowing their bounds in a pass are each tested against the bodies
/// of their slab of the sorted bounds (indexGuards); more, and the whole sweep is redone, with
/// every body's stretch (kGuardFactor) doubled for the rest of the step: a step whose impulses
/// turned that many bodies will turn them again in its later passes. On the 10 000-cube clump
/// 128, 1024 and no limit ran within 6 % of each other.
constexpr std::size_t kMaxDirectlyGrown = 128;
/// With no index sorted yet in the step, fewer outgrown bodies than this in a pass are each
/// tested against every body instead of sorting the bounds: sorting n bounds costs about what
/// a dozen scans over them do. On the 1000-cube clump's spray, where a body or two outgrows
/// its bounds in most steps, sorting every time took 2.6 % of the step.
constexpr std::size_t kMinIndexedGrown = 16;
/// An immovable body whose swept bounds are wider along x than this many times the widest
/// movable body's is not sorted into the index of growCandidates but tested directly, as the
/// sweep tests a ground (sweep_and_prune.cpp): it would reach into every slab.
constexpr double kIndexWidthRatio = 4.0;
}  // namespace

double ContactGathering::roundingSlack(const RigidBody& body, double halfDiagonal) {
  return kGuardRoundingSlack * (1.0 + body.s.x.cwiseAbs().maxCoeff() + halfDiagonal);
}

void ContactGathering::setGuard(const World& world, int i, const Vec3& gravityStep, double dt) {
  const RigidBody& body = world.bodies[i];
  const Obb box = Obb::of(body);
  guardStamp_[i] = ++stampCounter_;
  obbBounds(box, 0.0, guardLo_[i], guardHi_[i]);
  if (body.immovable) return;
  const double factor = kGuardFactor * guardScale_;
  const Vec3 shift = (factor * dt) * (body.v + gravityStep);
  const double spin = factor * dt * body.omega.norm() * halfDiagonal_[i];
  const double sideways = kGuardSideways * shift.norm() / factor + spin;
  guardLo_[i] = guardLo_[i].cwiseMin(guardLo_[i] + shift) - Vec3::Constant(sideways);
  guardHi_[i] = guardHi_[i].cwiseMax(guardHi_[i] + shift) + Vec3::Constant(sideways);
  // The slow pairs come from these bounds too: they must hold the slow widening's, bit for bit.
  Vec3 slowLo, slowHi;
  obbBounds(box, params_.slowWidening * body.halfExtents.minCoeff(), slowLo, slowHi);
  guardLo_[i] = guardLo_[i].cwiseMin(slowLo);
  guardHi_[i] = guardHi_[i].cwiseMax(slowHi);
}

bool ContactGathering::withinGuard(const RigidBody& body, int i, const Vec3& displacement,
                                   double turn) const {
  // At the predicted pose the bounds are the current ones moved by the displacement and, as a
  // corner moves at most |ω| Δt ρ when the body turns, grown by at most that, up to rounding.
  const double slack = turn + roundingSlack(body, halfDiagonal_[i]);
  for (int k = 0; k < 3; ++k)
    if (!(lo_[i][k] + displacement[k] - slack >= guardLo_[i][k] &&
          hi_[i][k] + displacement[k] + slack <= guardHi_[i][k]))
      return false;
  return true;
}

void ContactGathering::sweepCandidates(const World& world, const Vec3& gravityStep, double dt) {
  const std::size_t n = world.bodies.size();
  guardLo_.resize(n);
  guardHi_.resize(n);
  guardStamp_.resize(n);
  for (std::size_t i = 0; i < n; ++i) setGuard(world, static_cast<int>(i), gravityStep, dt);
  ++sweeps_;
  candidates_.clear();
  hasCandidate_.assign(n, 0);
  grownKeys_.clear();
  // Sorted again when first needed (growCandidates), from these bounds.
  guardIndex_.valid = false;
  guardIndex_.regrown.clear();
  sweptKeys_ = candidatePairs(world, guardLo_, guardHi_, sweepMargin_);
  // The cached pairs among them (both lists in increasing (a, b) order): a sweep within the
  // step keeps the cache, which still names its pairs.
  std::size_t cached = 0;
  const auto keyOf = [&](std::size_t k) {
    return std::pair<int, int>(pairReach_[k].a, pairReach_[k].b);
  };
  for (const auto& [i, j] : sweptKeys_) {
    candidates_.push_back(Candidate{i, j, SeparatingAxisResult{}, false});
    hasCandidate_[i] = hasCandidate_[j] = 1;
    for (; cached < pairReach_.size() && keyOf(cached) < std::pair<int, int>(i, j); ++cached) {
    }
    if (cached < pairReach_.size() && keyOf(cached) == std::pair<int, int>(i, j))
      candidates_.back().cached = static_cast<int>(cached);
  }
}

void ContactGathering::indexGuards(const World& world) {
  const std::size_t n = world.bodies.size();
  // As the sweep does (sweep_and_prune.cpp): a ground or a wall, much wider than every movable
  // body, would make every slab reach it; it is tested directly, as are bounds that cannot be
  // sorted (a state gone to NaN).
  double widest = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    if (!world.bodies[i].immovable && std::isfinite(guardHi_[i].x() - guardLo_[i].x()))
      widest = std::max(widest, guardHi_[i].x() - guardLo_[i].x());
  guardIndex_.order.clear();
  guardIndex_.direct.clear();
  for (std::size_t i = 0; i < n; ++i) {
    const double width = guardHi_[i].x() - guardLo_[i].x();
    const bool wide = world.bodies[i].immovable && !(width <= kIndexWidthRatio * widest);
    if (wide || !guardLo_[i].allFinite() || !guardHi_[i].allFinite())
      guardIndex_.direct.push_back(static_cast<int>(i));
    else
      guardIndex_.order.push_back(static_cast<int>(i));
  }
  std::sort(guardIndex_.order.begin(), guardIndex_.order.end(), [&](int i, int j) {
    return guardLo_[i].x() < guardLo_[j].x() || (guardLo_[i].x() == guardLo_[j].x() && i < j);
  });
  const std::size_t m = guardIndex_.order.size();
  guardIndex_.lo.resize(m);
  guardIndex_.maxHi.resize(m);
  double maxHi = -std::numeric_limits<double>::infinity();
  for (std::size_t p = 0; p < m; ++p) {
    const int i = guardIndex_.order[p];
    guardIndex_.lo[p] = guardLo_[i].x();
    maxHi = std::max(maxHi, guardHi_[i].x());
    guardIndex_.maxHi[p] = maxHi;
  }
  guardIndex_.stamp = stampCounter_;
  guardIndex_.valid = true;
  // Every body's bounds as they are now are in the sort.
  guardIndex_.regrown.clear();
}

template <class Visit>
void ContactGathering::forGuardsNear(const Vec3& lo, const Vec3& hi, double margin,
                                     const Visit& visit) const {
  const GuardIndex& index = guardIndex_;
  for (int j : index.direct) visit(j);
  // The bodies whose guard changed since the index was sorted stand where they are no more.
  for (int j : index.regrown) visit(j);
  // boundsWithin along x, with A the query and B body j: lo_j - hi <= margin and
  // lo - hi_j <= margin. The first fails for every body from the first that fails it on, the
  // order being by lo_j; the second for every body up to the last whose running largest hi_j
  // fails it. Both bounds are the test's own subtractions, so they skip no body it would pass.
  const auto first = std::partition_point(index.maxHi.begin(), index.maxHi.end(),
                                          [&](double maxHi) { return lo.x() - maxHi > margin; });
  for (std::size_t p = static_cast<std::size_t>(first - index.maxHi.begin());
       p < index.lo.size() && index.lo[p] - hi.x() <= margin; ++p) {
    const int j = index.order[p];
    if (guardStamp_[j] <= index.stamp) visit(j);
  }
}

void ContactGathering::growCandidates(const World& world, const Vec3& gravityStep, double dt,
                                      const std::vector<int>& outgrown) {
  // Many at once (a clump's first impact): one sweep is cheaper than testing each apart.
  if (outgrown.size() > kMaxDirectlyGrown) {
    guardScale_ *= 2.0;
    sweepCandidates(world, gravityStep, dt);
    return;
  }
  const bool indexed = guardIndex_.valid || outgrown.size() >= kMinIndexedGrown;
  if (indexed && !guardIndex_.valid) indexGuards(world);
  std::vector<char>& isOutgrown = isOutgrown_;
  isOutgrown.assign(world.bodies.size(), 0);
  for (int i : outgrown) {
    // Listed once: a body whose bounds were set since the sort is listed already.
    if (indexed && guardStamp_[i] <= guardIndex_.stamp) guardIndex_.regrown.push_back(i);
    setGuard(world, i, gravityStep, dt);
    isOutgrown[i] = 1;
  }
  // Each outgrown body against the bodies near it (from the index, or all of them), by the
  // sweep's test on the new bounds (a pair of two outgrown bodies once, from its lower index).
  std::vector<std::pair<int, int>> found;
  const auto test = [&](int i, int j) {
    if (j == i || (isOutgrown[j] && j < i)) return;
    if (world.bodies[i].immovable && world.bodies[j].immovable) return;
    if (boundsWithin(guardLo_[i], guardHi_[i], guardLo_[j], guardHi_[j], sweepMargin_)) {
      found.emplace_back(std::min(i, j), std::max(i, j));
      hasCandidate_[i] = hasCandidate_[j] = 1;
    }
  };
  const int n = static_cast<int>(world.bodies.size());
  for (int i : outgrown) {
    if (indexed)
      forGuardsNear(guardLo_[i], guardHi_[i], sweepMargin_, [&](int j) { test(i, j); });
    else
      for (int j = 0; j < n; ++j) test(i, j);
  }
  // A body tested directly whose bounds were set again is visited twice.
  std::sort(found.begin(), found.end());
  found.erase(std::unique(found.begin(), found.end()), found.end());
  // Appended after the sweep's pairs, which stay in place with what they remember of their
  // axis: merging into the (a, b) order copied every candidate, in every pass something grew.
  // Looked up among the keys alone: a search through the candidates themselves, 96 bytes
  // apiece, missed the cache at every probe.
  // The keys added now follow the sorted ones and are merged into them at the end (`found`
  // holds each pair once, so none of them needs looking up among the others).
  const auto grown = static_cast<std::ptrdiff_t>(grownKeys_.size());
  for (const std::pair<int, int>& key : found) {
    if (std::binary_search(sweptKeys_.begin(), sweptKeys_.end(), key)) continue;
    if (std::binary_search(grownKeys_.begin(), grownKeys_.begin() + grown, key)) continue;
    candidates_.push_back(Candidate{key.first, key.second, SeparatingAxisResult{}, false});
    grownKeys_.push_back(key);
  }
  std::inplace_merge(grownKeys_.begin(), grownKeys_.begin() + grown, grownKeys_.end());
}

bool ContactGathering::stepPairs(const World& world, double margin,
                                 std::vector<std::pair<int, int>>& pairs) const {
  if (params_.gathering != ContactGatheringMode::OncePerStep || !cacheCovers(world) ||
      !(margin <= sweepMargin_) || guardLo_.size() != world.bodies.size())
    return false;
  const std::size_t n = world.bodies.size();
  std::vector<Vec3> lo(n), hi(n);
  std::vector<char> outside(n, 0);
  std::vector<int> outsiders;
  for (std::size_t i = 0; i < n; ++i) {
    obbBounds(Obb::of(world.bodies[i]), 0.0, lo[i], hi[i]);
    // Inside, bound for bound: then guardLo_[b] - guardHi_[a] <= lo[b] - hi[a] in floating
    // point too (subtraction rounds monotonically), so a pair within the margin here was
    // within the sweep's margin there, and is a candidate. NaN bounds count as outside.
    if (!((lo[i].array() >= guardLo_[i].array()).all() &&
          (hi[i].array() <= guardHi_[i].array()).all())) {
      outside[i] = 1;
      outsiders.push_back(static_cast<int>(i));
    }
  }
  if (outsiders.size() > kMaxDirectlyGrown) return false;
  std::vector<std::pair<int, int>> found;
  for (const Candidate& c : candidates_)
    if (!outside[c.a] && !outside[c.b] && boundsWithin(lo[c.a], hi[c.a], lo[c.b], hi[c.b], margin))
      found.emplace_back(c.a, c.b);
  // The bodies outside their bounds against every body, as the broad phase would test them (a
  // pair of two such bodies once, from its lower index).
  for (int i : outsiders)
    for (std::size_t jj = 0; jj < n; ++jj) {
      const int j = static_cast<int>(jj);
      if (j == i || (outside[jj] && j < i)) continue;
      if (world.bodies[i].immovable && world.bodies[jj].immovable) continue;
      if (boundsWithin(lo[i], hi[i], lo[jj], hi[jj], margin))
        found.emplace_back(std::min(i, j), std::max(i, j));
    }
  if (!outsiders.empty() || !grownKeys_.empty())
    std::sort(found.begin(), found.end());
  pairs.swap(found);
  return true;
}

}  // namespace boxsim
