/// \file
/// The step's candidate pairs of the once-per-step gathering.
#include "boxsim/impulse_damped/step_candidates.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/collision/obb.hpp"

namespace boxsim {

namespace {
/// A body's swept bounds are stretched this many times its displacement in a pass along that
/// displacement, so its velocity may grow this much along its way under the impulses of the
/// step before its pairs are looked for again.
constexpr double kSweptStretch = 1.5;
/// ... and grown on every side by this fraction of that displacement (and kSweptStretch times
/// what its spin can move a corner), for a velocity that turns.
/// Only speed depends on the two: smaller swept bounds give fewer candidates and a cheaper
/// sweep, and more bodies that outgrow them and are tested again. On the clump of Fig. 6.7
/// (1000 cubes, callgrind) 1.5 and 0.5 took 6 % fewer instructions than 2 and 1, and fewer than
/// 1.5 and 0.25 or 1.25 and 0.25.
constexpr double kSweptSideways = 0.5;
/// Relative slack for rounding (obbBounds at two poses round differently, by a few ulp of the
/// coordinates), times the size of the coordinates plus one metre.
constexpr double kBoundsRoundingSlack = 1e-9;

/// Up to this many bodies outgrowing their swept bounds in a pass are each tested against the
/// bodies of their slab of the sorted bounds (indexSweptBounds); more, and the whole sweep is
/// redone, with every body's stretch doubled for the rest of the step: a step whose impulses
/// turned that many bodies will turn them again in its later passes. On the 10 000-cube clump
/// 128, 1024 and no limit ran within 6 % of each other.
constexpr std::size_t kMaxDirectlyGrown = 128;
/// With no index sorted yet in the step, fewer outgrown bodies than this in a pass are each
/// tested against every body instead of sorting the bounds: sorting n bounds costs about what
/// a dozen scans over them do. On the 1000-cube clump's spray, where a body or two outgrows
/// its bounds in most steps, sorting every time took 2.6 % of the step.
constexpr std::size_t kMinIndexedGrown = 16;
/// An immovable body whose swept bounds are wider along x than this many times the widest
/// movable body's is not sorted into the index but tested directly, as the sweep tests a
/// ground (sweep_and_prune.cpp): it would reach into every slab.
constexpr double kIndexWidthRatio = 4.0;
}  // namespace

double boundsRoundingSlack(const RigidBody& body, double halfDiagonal) {
  return kBoundsRoundingSlack * (1.0 + body.s.x.cwiseAbs().maxCoeff() + halfDiagonal);
}

void StepCandidates::setSweptBounds(const World& world, const StepBodies& bodies, int i,
                                    const Vec3& gravityStep, double dt, StampCounter& stamps) {
  const RigidBody& body = world.bodies[i];
  const Obb box = Obb::of(body);
  sweptStamp_[i] = stamps.next();
  obbBounds(box, 0.0, sweptLo_[i], sweptHi_[i]);
  if (body.immovable) return;
  const double factor = kSweptStretch * stretch_;
  const Vec3 shift = (factor * dt) * (body.v + gravityStep);
  const double spin = factor * dt * body.omega.norm() * bodies.halfDiagonal[i];
  const double sideways = kSweptSideways * shift.norm() / factor + spin;
  sweptLo_[i] = sweptLo_[i].cwiseMin(sweptLo_[i] + shift) - Vec3::Constant(sideways);
  sweptHi_[i] = sweptHi_[i].cwiseMax(sweptHi_[i] + shift) + Vec3::Constant(sideways);
  // The slow pairs come from these bounds too: they must hold the slow widening's, bit for bit.
  Vec3 slowLo, slowHi;
  obbBounds(box, slowWidening_ * body.halfExtents.minCoeff(), slowLo, slowHi);
  sweptLo_[i] = sweptLo_[i].cwiseMin(slowLo);
  sweptHi_[i] = sweptHi_[i].cwiseMax(slowHi);
}

bool StepCandidates::withinSweptBounds(const RigidBody& body, int i, const StepBodies& bodies,
                                       const Vec3& displacement, double turn) const {
  // At the predicted pose the bounds are the current ones moved by the displacement and, as a
  // corner moves at most |ω| Δt ρ when the body turns, grown by at most that, up to rounding.
  const double slack = turn + boundsRoundingSlack(body, bodies.halfDiagonal[i]);
  for (int k = 0; k < 3; ++k)
    if (!(bodies.lo[i][k] + displacement[k] - slack >= sweptLo_[i][k] &&
          bodies.hi[i][k] + displacement[k] + slack <= sweptHi_[i][k]))
      return false;
  return true;
}

void StepCandidates::start(const World& world, const StepBodies& bodies,
                           const std::vector<PairReach>& cached, const Vec3& gravityStep,
                           double dt, double sweepMargin, StampCounter& stamps) {
  sweepMargin_ = sweepMargin;
  stretch_ = 1.0;
  sweep(world, bodies, cached, gravityStep, dt, stamps);
}

void StepCandidates::sweep(const World& world, const StepBodies& bodies,
                           const std::vector<PairReach>& cached, const Vec3& gravityStep,
                           double dt, StampCounter& stamps) {
  const std::size_t n = world.bodies.size();
  sweptLo_.resize(n);
  sweptHi_.resize(n);
  sweptStamp_.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    setSweptBounds(world, bodies, static_cast<int>(i), gravityStep, dt, stamps);
  ++sweeps_;
  // The candidates before this sweep: a pair that is a candidate again keeps the axis of its
  // last test. The last sweep's come first, by pair; those grow() added after them, few, are
  // sorted apart.
  previous_.swap(candidates_);
  const std::size_t previousSwept = std::min(sweptKeys_.size(), previous_.size());
  std::sort(previous_.begin() + static_cast<std::ptrdiff_t>(previousSwept), previous_.end(),
            [](const Candidate& x, const Candidate& y) {
              return std::pair<int, int>(x.a, x.b) < std::pair<int, int>(y.a, y.b);
            });
  candidates_.clear();
  hasCandidate_.assign(n, 0);
  grownKeys_.clear();
  // Sorted again when first needed (grow), from these bounds.
  index_.valid = false;
  index_.regrown.clear();
  candidatePairs(world, sweptLo_, sweptHi_, sweepMargin_, sweepAndPrune_, sweptKeys_);
  // Each new candidate finds its cached pair (a sweep within the step keeps the cache, which
  // still names its pairs) and its remembered axis: every list is in increasing (a, b) order,
  // as the sweep's pairs are, so one cursor each walks along.
  const auto seek = [](std::size_t& p, std::size_t last, const auto& keyAt,
                       const std::pair<int, int>& key) {
    for (; p < last && keyAt(p) < key; ++p) {
    }
    return p < last && keyAt(p) == key;
  };
  const auto cachedKey = [&](std::size_t c) { return std::pair<int, int>(cached[c].a, cached[c].b); };
  const auto previousKey = [&](std::size_t c) {
    return std::pair<int, int>(previous_[c].a, previous_[c].b);
  };
  std::size_t k = 0, p = 0, g = previousSwept;
  for (const auto& [i, j] : sweptKeys_) {
    const std::pair<int, int> key(i, j);
    candidates_.push_back(Candidate{i, j, SeparatingAxisResult{}, false});
    Candidate& candidate = candidates_.back();
    hasCandidate_[i] = hasCandidate_[j] = 1;
    // The axis of the pair's last test and its answer, if it was a candidate before (in the
    // last sweep's part or grow()'s): the one-axis check (separatedBeyond) proves a pair apart
    // whatever pose the axis came from, so an axis from an earlier step settles a pair still
    // apart along it as the full test would, without the test.
    const Candidate* before = seek(p, previousSwept, previousKey, key)       ? &previous_[p]
                              : seek(g, previous_.size(), previousKey, key) ? &previous_[g]
                                                                            : nullptr;
    if (before) {
      candidate.axis = before->axis;
      candidate.apart = before->apart;
      // Within a step (a sweep grow() redoes) the pair stays gathered as it was; the cache's
      // build decides afresh at a step's start.
      candidate.exactEach = before->exactEach;
    }
    if (seek(k, cached.size(), cachedKey, key)) candidate.cached = static_cast<int>(k);
  }
}

void StepCandidates::indexSweptBounds(const World& world, const StampCounter& stamps) {
  const std::size_t n = world.bodies.size();
  // As the sweep does (sweep_and_prune.cpp): a ground or a wall, much wider than every movable
  // body, would make every slab reach it; it is tested directly, as are bounds that cannot be
  // sorted (a state gone to NaN).
  double widest = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    if (!world.bodies[i].immovable && std::isfinite(sweptHi_[i].x() - sweptLo_[i].x()))
      widest = std::max(widest, sweptHi_[i].x() - sweptLo_[i].x());
  index_.order.clear();
  index_.direct.clear();
  for (std::size_t i = 0; i < n; ++i) {
    const double width = sweptHi_[i].x() - sweptLo_[i].x();
    const bool wide = world.bodies[i].immovable && !(width <= kIndexWidthRatio * widest);
    if (wide || !sweptLo_[i].allFinite() || !sweptHi_[i].allFinite())
      index_.direct.push_back(static_cast<int>(i));
    else
      index_.order.push_back(static_cast<int>(i));
  }
  std::sort(index_.order.begin(), index_.order.end(), [&](int i, int j) {
    return sweptLo_[i].x() < sweptLo_[j].x() || (sweptLo_[i].x() == sweptLo_[j].x() && i < j);
  });
  const std::size_t m = index_.order.size();
  index_.lo.resize(m);
  index_.maxHi.resize(m);
  double maxHi = -std::numeric_limits<double>::infinity();
  for (std::size_t p = 0; p < m; ++p) {
    const int i = index_.order[p];
    index_.lo[p] = sweptLo_[i].x();
    maxHi = std::max(maxHi, sweptHi_[i].x());
    index_.maxHi[p] = maxHi;
  }
  index_.stamp = stamps.last;
  index_.valid = true;
  // Every body's bounds as they are now are in the sort.
  index_.regrown.clear();
}

template <class Visit>
void StepCandidates::forSweptBoundsNear(const Vec3& lo, const Vec3& hi, double margin,
                                        const Visit& visit) const {
  for (int j : index_.direct) visit(j);
  // The bodies whose bounds changed since the index was sorted stand where they are no more.
  for (int j : index_.regrown) visit(j);
  // boundsWithin along x, with A the query and B body j: lo_j - hi <= margin and
  // lo - hi_j <= margin. The first fails for every body from the first that fails it on, the
  // order being by lo_j; the second for every body up to the last whose running largest hi_j
  // fails it. Both bounds are the test's own subtractions, so they skip no body it would pass.
  const auto first = std::partition_point(index_.maxHi.begin(), index_.maxHi.end(),
                                          [&](double maxHi) { return lo.x() - maxHi > margin; });
  for (std::size_t p = static_cast<std::size_t>(first - index_.maxHi.begin());
       p < index_.lo.size() && index_.lo[p] - hi.x() <= margin; ++p) {
    const int j = index_.order[p];
    if (sweptStamp_[j] <= index_.stamp) visit(j);
  }
}

void StepCandidates::grow(const World& world, const StepBodies& bodies,
                          const std::vector<PairReach>& cached, const Vec3& gravityStep,
                          double dt, const std::vector<int>& outgrown, StampCounter& stamps) {
  // Many at once (a clump's first impact): one sweep is cheaper than testing each apart.
  if (outgrown.size() > kMaxDirectlyGrown) {
    stretch_ *= 2.0;
    sweep(world, bodies, cached, gravityStep, dt, stamps);
    return;
  }
  const bool indexed = index_.valid || outgrown.size() >= kMinIndexedGrown;
  if (indexed && !index_.valid) indexSweptBounds(world, stamps);
  std::vector<char>& isOutgrown = isOutgrown_;
  isOutgrown.assign(world.bodies.size(), 0);
  for (int i : outgrown) {
    // Listed once: a body whose bounds were set since the sort is listed already.
    if (indexed && sweptStamp_[i] <= index_.stamp) index_.regrown.push_back(i);
    setSweptBounds(world, bodies, i, gravityStep, dt, stamps);
    isOutgrown[i] = 1;
  }
  // Each outgrown body against the bodies near it (from the index, or all of them), by the
  // sweep's test on the new bounds (a pair of two outgrown bodies once, from its lower index).
  std::vector<std::pair<int, int>>& found = found_;
  found.clear();
  const auto test = [&](int i, int j) {
    if (j == i || (isOutgrown[j] && j < i)) return;
    if (world.bodies[i].immovable && world.bodies[j].immovable) return;
    if (boundsWithin(sweptLo_[i], sweptHi_[i], sweptLo_[j], sweptHi_[j], sweepMargin_)) {
      found.emplace_back(std::min(i, j), std::max(i, j));
      hasCandidate_[i] = hasCandidate_[j] = 1;
    }
  };
  const int n = static_cast<int>(world.bodies.size());
  for (int i : outgrown) {
    if (indexed)
      forSweptBoundsNear(sweptLo_[i], sweptHi_[i], sweepMargin_, [&](int j) { test(i, j); });
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

void StepCandidates::indexByBody(std::size_t n) {
  if (byBodySweep_ == sweeps_ && byBodyCount_ == candidates_.size() &&
      byBodyStart_.size() == n + 1)
    return;
  byBodyStart_.assign(n + 1, 0);
  for (const Candidate& c : candidates_) {
    ++byBodyStart_[static_cast<std::size_t>(c.a) + 1];
    ++byBodyStart_[static_cast<std::size_t>(c.b) + 1];
  }
  for (std::size_t i = 0; i < n; ++i) byBodyStart_[i + 1] += byBodyStart_[i];
  byBody_.resize(static_cast<std::size_t>(byBodyStart_[n]));
  byBodyFill_.assign(byBodyStart_.begin(), byBodyStart_.end() - 1);
  for (std::size_t k = 0; k < candidates_.size(); ++k)
    for (const int body : {candidates_[k].a, candidates_[k].b})
      byBody_[static_cast<std::size_t>(byBodyFill_[static_cast<std::size_t>(body)]++)] =
          static_cast<int>(k);
  byBodySweep_ = sweeps_;
  byBodyCount_ = candidates_.size();
}

bool StepCandidates::pairsAt(const World& world, double margin,
                             std::vector<std::pair<int, int>>& pairs) const {
  if (!(margin <= sweepMargin_) || sweptLo_.size() != world.bodies.size()) return false;
  const std::size_t n = world.bodies.size();
  std::vector<Vec3>& lo = nowLo_;
  std::vector<Vec3>& hi = nowHi_;
  std::vector<char>& outside = outside_;
  std::vector<int>& outsiders = outsiders_;
  lo.resize(n);
  hi.resize(n);
  outside.assign(n, 0);
  outsiders.clear();
  for (std::size_t i = 0; i < n; ++i) {
    obbBounds(Obb::of(world.bodies[i]), 0.0, lo[i], hi[i]);
    // Inside, bound for bound: then sweptLo_[b] - sweptHi_[a] <= lo[b] - hi[a] in floating
    // point too (subtraction rounds monotonically), so a pair within the margin here was
    // within the sweep's margin there, and is a candidate. NaN bounds count as outside.
    if (!((lo[i].array() >= sweptLo_[i].array()).all() &&
          (hi[i].array() <= sweptHi_[i].array()).all())) {
      outside[i] = 1;
      outsiders.push_back(static_cast<int>(i));
    }
  }
  if (outsiders.size() > kMaxDirectlyGrown) return false;
  std::vector<std::pair<int, int>>& found = pairs;
  found.clear();
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
  return true;
}

}  // namespace boxsim
