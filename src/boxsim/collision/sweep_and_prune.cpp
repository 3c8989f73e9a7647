/// \file
/// Sweep and prune over the bodies' axis-aligned bounds (\thesis{§4.1} names spatial
/// subdivision as what larger scenes need). Three stages: sort the movable bodies along one
/// axis and sweep, test the few immovable bodies directly, then put the pairs into the
/// all-pairs order. Every reported pair passes boundsWithin, the test the all-pairs loop uses,
/// and the sweep's early exit only skips pairs that test would reject, so both broad phases
/// return the same list.
#include "boxsim/collision/sweep_and_prune.hpp"

#include <algorithm>
#include <cstddef>

#include "boxsim/collision/broad_phase.hpp"

namespace boxsim {

namespace {

/// A swept body's bounds along the sweep axis, m: the element the sweep sorts, kept apart
/// from the full bounds so the inner loop walks contiguous memory.
/// An immovable body is swept like the others unless its largest half extent is more than this
/// many times the largest half extent of any movable body: then it is a ground or a wall.
constexpr double kSweptSizeRatio = 4.0;

struct Interval {
  double lo = 0.0;
  double hi = 0.0;
  int body = -1;
};

/// The world axis (0, 1, 2) along which the centres of `bodies` spread most (largest
/// variance), the lowest such axis on a tie. Spreading the intervals thinly keeps the number
/// of pairs that overlap along the sweep axis alone close to the number that overlap on all
/// three. Only speed depends on this choice, never the result.
int axisOfLargestSpread(const World& world, const std::vector<int>& bodies) {
  Vec3 mean = Vec3::Zero();
  for (int i : bodies) mean += world.bodies[i].s.x;
  mean /= static_cast<double>(bodies.size());
  Vec3 variance = Vec3::Zero();
  for (int i : bodies) variance += (world.bodies[i].s.x - mean).cwiseAbs2();
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (variance[k] > variance[axis]) axis = k;
  return axis;
}

/// Puts pairs (i, j) with 0 <= i, j < n into increasing (i, j) order in O(n + k) for k pairs:
/// a stable counting sort by j, then one by i (least significant key first).
void sortPairs(std::vector<std::pair<int, int>>& pairs, int n) {
  std::vector<std::pair<int, int>> sorted(pairs.size());
  const auto countingSortBy = [&](int std::pair<int, int>::*key) {
    std::vector<std::size_t> start(static_cast<std::size_t>(n) + 1, 0);
    for (const std::pair<int, int>& p : pairs) ++start[p.*key + 1];
    for (int v = 0; v < n; ++v) start[v + 1] += start[v];
    for (const std::pair<int, int>& p : pairs) sorted[start[p.*key]++] = p;
    pairs.swap(sorted);
  };
  countingSortBy(&std::pair<int, int>::second);
  countingSortBy(&std::pair<int, int>::first);
}

}  // namespace

std::vector<std::pair<int, int>> sweepAndPrunePairs(const World& world, double margin,
                                                    const std::vector<double>& growth) {
  const int n = static_cast<int>(world.bodies.size());
  std::vector<Vec3> lo(n), hi(n);
  for (int i = 0; i < n; ++i)
    obbBounds(Obb::of(world.bodies[i]), growth.empty() ? 0.0 : growth[i], lo[i], hi[i]);

  // A ground as wide as the scene, swept, would overlap every interval along the sweep axis and
  // make the sweep quadratic: immovable bodies much larger than every movable one are tested
  // directly. Sleeping bodies standing in as immovable (§4.5) are box-sized and many, so they
  // are swept: tested directly, they made the sweep quadratic in the number of sleepers. Bounds
  // that are not finite (a state gone to NaN) cannot be sorted, so they are tested directly
  // too, which keeps the result equal to the all-pairs one even then.
  double largestMovable = 0.0;
  for (const RigidBody& b : world.bodies)
    if (!b.immovable) largestMovable = std::max(largestMovable, b.halfExtents.maxCoeff());
  std::vector<int> direct, swept;
  swept.reserve(n);
  std::vector<char> isDirect(n, 0);
  for (int i = 0; i < n; ++i) {
    const RigidBody& b = world.bodies[i];
    const bool huge = b.immovable && !(b.halfExtents.maxCoeff() <= kSweptSizeRatio * largestMovable);
    isDirect[i] = huge || !lo[i].allFinite() || !hi[i].allFinite();
    (isDirect[i] ? direct : swept).push_back(i);
  }

  // Bodies resting in a stack touch a handful of neighbours each, so 4 n pairs is usually
  // room enough for all of them from the start (it is only a starting capacity).
  std::vector<std::pair<int, int>> pairs;
  pairs.reserve(4 * static_cast<std::size_t>(n));
  for (int d : direct) {
    for (int j = 0; j < n; ++j) {
      // A pair of two direct bodies is tested once, from its lower index.
      if (j == d || (isDirect[j] && j < d)) continue;
      // Two immovable bodies (ground and wall) never need a contact between them.
      if (world.bodies[d].immovable && world.bodies[j].immovable) continue;
      if (boundsWithin(lo[d], hi[d], lo[j], hi[j], margin))
        pairs.emplace_back(std::min(d, j), std::max(d, j));
    }
  }

  if (!swept.empty()) {
    const int axis = axisOfLargestSpread(world, swept);
    std::vector<Interval> intervals;
    intervals.reserve(swept.size());
    for (int i : swept) intervals.push_back(Interval{lo[i][axis], hi[i][axis], i});
    // Ties broken by body index make the order total, so std::sort (not stable) sweeps the
    // same way on every run and every standard library. The result would not change without
    // it, since sortPairs orders the pairs anyway, but a sweep that can be replayed can be
    // debugged.
    std::sort(intervals.begin(), intervals.end(), [](const Interval& a, const Interval& b) {
      return a.lo < b.lo || (a.lo == b.lo && a.body < b.body);
    });

    // The bounds in sweep order, so the inner loop reads memory in sequence instead of
    // jumping to each body's bounds by index.
    const std::size_t m = intervals.size();
    std::vector<Vec3> sortedLo(m), sortedHi(m);
    for (std::size_t p = 0; p < m; ++p) {
      sortedLo[p] = lo[intervals[p].body];
      sortedHi[p] = hi[intervals[p].body];
    }

    for (std::size_t p = 0; p < m; ++p) {
      const double end = intervals[p].hi;
      for (std::size_t q = p + 1; q < m; ++q) {
        // intervals[q].lo never decreases with q and rounding is monotone, so once
        // intervals[q].lo - end exceeds margin it does for every later q: boundsWithin would
        // reject them all along this axis.
        if (intervals[q].lo - end > margin) break;
        if (boundsWithin(sortedLo[p], sortedHi[p], sortedLo[q], sortedHi[q], margin)) {
          const int a = intervals[p].body, b = intervals[q].body;
          if (world.bodies[a].immovable && world.bodies[b].immovable) continue;
          pairs.emplace_back(std::min(a, b), std::max(a, b));
        }
      }
    }
  }

  sortPairs(pairs, n);
  return pairs;
}

}  // namespace boxsim
