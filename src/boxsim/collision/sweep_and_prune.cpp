/// \file
/// Sweep and prune over the bodies' axis-aligned bounds (\thesis{§4.1} names spatial
/// subdivision as what larger scenes need). Three stages: sort the movable bodies along one
/// axis and sweep, test the few immovable bodies directly, then put the pairs into the
/// all-pairs order. Every reported pair passes boundsWithin, the test the all-pairs loop uses,
/// and the sweep's early exit only skips pairs that test would reject, so both broad phases
/// return the same list.
#include "boxsim/collision/sweep_and_prune.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <memory>
#include <stdexcept>

#include "boxsim/collision/broad_phase.hpp"

namespace boxsim {

namespace {

/// An immovable body is swept like the others unless its largest half extent is more than this
/// many times the largest half extent of any movable body: then it is a ground or a wall.
constexpr double kSweptSizeRatio = 4.0;
/// Swept bodies from this many on are paired through a uniform grid instead of the sweep: a
/// regular arrangement (the clump of Fig. 6.7, a pyramid) makes the sweep's candidate list grow
/// faster than n, the grid's stays linear.
constexpr std::size_t kGridMinBodies = 64;
/// In the grid, a body larger than this many times the median extent is tested directly, so a
/// few large boxes do not make every cell large.
constexpr double kGridSizeRatio = 4.0;
/// The grid is used only when it has at most this many cells per gridded body (its memory and
/// its sweep over empty cells stay linear); a scattered scene goes to the sweep.
constexpr double kGridCellsPerBody = 8.0;
/// The grid's cells are sized for the bodies up to this quantile of the extents; the wider
/// bodies above it (up to kGridSizeRatio times the median) are not put into cells but looked up
/// in every cell they can reach. The cells' volume, and with it the pairs each body is tested
/// against, falls with the cube of their width: on the collapsing clump of 10 000 cubes, whose
/// swept bounds spread from 1.9 to 2.7 m, cells sized for the widest made 13 tests a pair found.
/// Measured there (instructions of the broad phase, 2 s): 0.75 and 0.9 leave too many wide
/// bodies to sweep among themselves; 0.95 and 0.97 do best, 0.99 a little worse.
constexpr double kGridCellQuantile = 0.95;

}  // namespace

/// The types SweepAndPrune::Lists holds (Interval, Grid). A class with external linkage whose
/// members have types of an anonymous namespace draws -Wsubobject-linkage once the file is
/// compiled inside another (the unity builds), so they live in a named namespace of their own.
namespace sweep_and_prune_lists {

/// A swept body's bounds along the sweep axis, m: the element the sweep sorts, kept apart
/// from the full bounds so the inner loop walks contiguous memory.
struct Interval {
  double lo = 0.0;  ///< m, the lower end of the body's bounds along the sweep axis
  double hi = 0.0;  ///< m, the upper end
  int body = -1;    ///< the body's index in the world
};

/// A uniform grid over the gridded bodies: each body sits in the cell of the lower corner of its
/// bounds, and the cells are at least as wide as any gridded body's bounds plus the margin, so
/// two gridded bodies whose bounds come within the margin sit in the same or in adjacent cells.
/// Bodies wider than that (`wide`) are not in the cells: each looks into the cells it can reach.
struct Grid {
  Vec3 origin = Vec3::Zero();                   ///< lower corner of cell (0, 0, 0), m
  double h = 1.0;                               ///< cell width, m
  Eigen::Vector3i dims = Eigen::Vector3i::Ones();  ///< cells along x, y, z
  std::vector<int> start;  ///< bodies of cell c are order[start[c], start[c + 1])
  std::vector<int> order;  ///< gridded bodies by cell, by body index within a cell
  std::vector<int> cell;   ///< the cell of each body of `order`
  // Working lists of buildGrid and gridPairs, kept for their room.
  std::vector<double> extent;         ///< per swept body: its largest bounds extent, m
  std::vector<double> sortedExtent;   ///< a copy of the extents for their median (nth_element), m
  std::vector<int> gridded;           ///< the gridded bodies
  std::vector<int> wide;              ///< bodies wider than the cells, looked up (widePairs)
  std::vector<Interval> wideIntervals;  ///< the sweep of the wide bodies among themselves
  std::vector<Vec3> wideLo;           ///< the wide bodies' lower bounds in sweep order, m
  std::vector<Vec3> wideHi;           ///< the wide bodies' upper bounds in sweep order, m
  std::vector<int> cellOf;            ///< per gridded body: its cell
  std::vector<int> next;              ///< per cell: the fill cursor into `order`
  std::vector<Vec3> sortedLo;         ///< the lower bounds in `order`, m
  std::vector<Vec3> sortedHi;         ///< the upper bounds in `order`, m
  std::vector<char> sortedImmovable;  ///< per body of `order`: immovable
  std::vector<char> movableIn;        ///< per cell: holds a movable body
};

}  // namespace sweep_and_prune_lists

namespace {

using sweep_and_prune_lists::Grid;
using sweep_and_prune_lists::Interval;

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
/// `sorted` and `start` are working lists.
void sortPairs(std::vector<std::pair<int, int>>& pairs, int n,
               std::vector<std::pair<int, int>>& sorted, std::vector<std::size_t>& start) {
  sorted.resize(pairs.size());
  const auto countingSortBy = [&](int std::pair<int, int>::*key) {
    start.assign(static_cast<std::size_t>(n) + 1, 0);
    for (const std::pair<int, int>& p : pairs) ++start[p.*key + 1];
    for (int v = 0; v < n; ++v) start[v + 1] += start[v];
    for (const std::pair<int, int>& p : pairs) sorted[start[p.*key]++] = p;
    pairs.swap(sorted);
  };
  countingSortBy(&std::pair<int, int>::second);
  countingSortBy(&std::pair<int, int>::first);
}

/// Tests each directly tested body against every other body (a pair of two direct bodies once,
/// from its lower index), appending the pairs that pass boundsWithin.
void testDirect(const World& world, const std::vector<Vec3>& lo, const std::vector<Vec3>& hi,
                const std::vector<int>& direct, const std::vector<char>& isDirect, double margin,
                std::vector<std::pair<int, int>>& pairs) {
  const int n = static_cast<int>(world.bodies.size());
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
}

/// Sort and sweep over the `swept` bodies along the axis on which their centres spread most.
/// `intervals`, `sortedLo` and `sortedHi` are working lists.
void sweepPairs(const World& world, const std::vector<Vec3>& lo, const std::vector<Vec3>& hi,
                const std::vector<int>& swept, double margin,
                std::vector<std::pair<int, int>>& pairs, std::vector<Interval>& intervals,
                std::vector<Vec3>& sortedLo, std::vector<Vec3>& sortedHi) {
  if (swept.empty()) return;
  const int axis = axisOfLargestSpread(world, swept);
  intervals.clear();
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
  sortedLo.resize(m);
  sortedHi.resize(m);
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

/// Builds the grid over `swept`, or returns false when a grid would not pay (the cells would
/// outnumber the bodies many times: a scattered scene, which the sweep handles well). Bodies
/// more than kGridSizeRatio times the median extent would make every cell large: they move to
/// `direct` instead. The cells are as wide as the bodies up to kGridCellQuantile of the extents
/// (plus the margin); the wider ones go to Grid::wide (widePairs), unless cells that narrow
/// would be too many, when every body is gridded with cells as wide as the widest.
bool buildGrid(const std::vector<Vec3>& lo, const std::vector<Vec3>& hi,
               const std::vector<int>& swept, double margin, std::vector<int>& direct,
               std::vector<char>& isDirect, Grid& grid) {
  std::vector<double>& extent = grid.extent;
  extent.resize(swept.size());
  for (std::size_t k = 0; k < swept.size(); ++k)
    extent[k] = (hi[swept[k]] - lo[swept[k]]).maxCoeff();
  std::vector<double>& sorted = grid.sortedExtent;
  sorted.assign(extent.begin(), extent.end());
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(sorted.size() / 2), sorted.end());
  const double median = sorted[sorted.size() / 2];
  const std::size_t q =
      static_cast<std::size_t>(kGridCellQuantile * static_cast<double>(sorted.size() - 1));
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<long>(q), sorted.end());
  const double quantile = sorted[q];
  // Cells for the bodies up to the quantile, the wider ones looked up; if that grid would be
  // too fine for the scene, cells for every gridded body as wide as the widest.
  double cells = 1.0;
  for (const bool lookUpWide : {true, false}) {
    std::vector<int>& gridded = grid.gridded;
    std::vector<int>& wide = grid.wide;
    gridded.clear();
    wide.clear();
    double largest = 0.0;
    Vec3 lowest = Vec3::Constant(std::numeric_limits<double>::infinity());
    Vec3 highest = -lowest;
    double scale = 0.0;
    for (std::size_t k = 0; k < swept.size(); ++k) {
      if (extent[k] > kGridSizeRatio * median) continue;
      scale = std::max(scale, hi[swept[k]].cwiseAbs().maxCoeff());
      if (lookUpWide && extent[k] > quantile) {
        wide.push_back(swept[k]);
        continue;
      }
      gridded.push_back(swept[k]);
      largest = std::max(largest, extent[k]);
      lowest = lowest.cwiseMin(lo[swept[k]]);
      highest = highest.cwiseMax(lo[swept[k]]);
    }
    // Slack for rounding: cell indices come from (lo - origin) / h in floating point, and a
    // pair whose lower corners are a hair less than h apart must never land two cells apart.
    grid.h = (largest + margin) * (1.0 + 1e-6) + 1e-9 * scale + 1e-300;
    grid.origin = lowest;
    cells = 1.0;
    for (int k = 0; k < 3; ++k) {
      const double d = std::floor((highest[k] - lowest[k]) / grid.h) + 1.0;
      cells *= d;
      grid.dims[k] = static_cast<int>(std::min(d, 1e9));
    }
    if (cells <= kGridCellsPerBody * static_cast<double>(gridded.size())) break;
    if (!lookUpWide) return false;
  }
  const std::vector<int>& gridded = grid.gridded;

  for (std::size_t k = 0; k < swept.size(); ++k)
    if (extent[k] > kGridSizeRatio * median) {
      direct.push_back(swept[k]);
      isDirect[swept[k]] = 1;
    }
  // Counting sort of the bodies by cell; bodies keep their index order within a cell.
  std::vector<int>& cellOf = grid.cellOf;
  cellOf.resize(gridded.size());
  grid.start.assign(static_cast<std::size_t>(cells) + 1, 0);
  for (std::size_t g = 0; g < gridded.size(); ++g) {
    const Vec3 c = ((lo[gridded[g]] - grid.origin) / grid.h).array().floor();
    cellOf[g] = (static_cast<int>(c.z()) * grid.dims.y() + static_cast<int>(c.y())) * grid.dims.x() +
                static_cast<int>(c.x());
    ++grid.start[static_cast<std::size_t>(cellOf[g]) + 1];
  }
  for (std::size_t c = 1; c < grid.start.size(); ++c) grid.start[c] += grid.start[c - 1];
  grid.order.resize(gridded.size());
  grid.cell.resize(gridded.size());
  std::vector<int>& next = grid.next;
  next.assign(grid.start.begin(), grid.start.end() - 1);
  for (std::size_t g = 0; g < gridded.size(); ++g) {
    const int at = next[cellOf[g]]++;
    grid.order[at] = gridded[g];
    grid.cell[at] = cellOf[g];
  }
  return true;
}

/// The pairs of the wide bodies (Grid::wide), each with the gridded bodies of every cell whose
/// bodies it can come within `margin` of, and with each other. A gridded body B near a wide one
/// X has, along each axis, its lower end within [lo_X - h, hi_X + margin] (B's extent plus the
/// margin is under the cell width h), so X looks in the cells of that box, widened by a
/// millionth of h for the rounding of the bounds of the box itself.
void widePairs(const World& world, const std::vector<Vec3>& lo, const std::vector<Vec3>& hi,
               Grid& grid, double margin, std::vector<std::pair<int, int>>& pairs) {
  const Eigen::Vector3i& d = grid.dims;
  const double slack = 1e-6 * grid.h;
  const auto cellIndex = [&](double v, int k) {
    const double c = std::floor((v - grid.origin[k]) / grid.h);
    return static_cast<int>(std::clamp(c, 0.0, static_cast<double>(d[k] - 1)));
  };
  for (const int x : grid.wide) {
    const bool immovable = world.bodies[x].immovable;
    Eigen::Vector3i from, to;
    for (int k = 0; k < 3; ++k) {
      from[k] = cellIndex(lo[x][k] - grid.h - slack, k);
      to[k] = cellIndex(hi[x][k] + margin + slack, k);
    }
    for (int cz = from.z(); cz <= to.z(); ++cz)
      for (int cy = from.y(); cy <= to.y(); ++cy)
        for (int cx = from.x(); cx <= to.x(); ++cx) {
          const int c = (cz * d.y() + cy) * d.x() + cx;
          if (immovable && !grid.movableIn[static_cast<std::size_t>(c)]) continue;
          for (int q = grid.start[c]; q < grid.start[c + 1]; ++q) {
            if (immovable && grid.sortedImmovable[q]) continue;
            if (boundsWithin(lo[x], hi[x], grid.sortedLo[q], grid.sortedHi[q], margin)) {
              const int b = grid.order[q];
              pairs.emplace_back(std::min(x, b), std::max(x, b));
            }
          }
        }
  }
  // The wide bodies among themselves: too many to pair each with each (a twentieth of the
  // bodies), so swept.
  sweepPairs(world, lo, hi, grid.wide, margin, pairs, grid.wideIntervals, grid.wideLo,
             grid.wideHi);
}

/// The pairs of gridded bodies: each occupied cell against itself and its 13 neighbours that
/// follow it (dz > 0, or dz = 0 and dy > 0, or dz = dy = 0 and dx > 0), so each pair of cells
/// is visited once. The bounds are copied into cell order first, so the scans read memory in
/// sequence; only the occupied cells are visited.
void gridPairs(const World& world, const std::vector<Vec3>& lo, const std::vector<Vec3>& hi,
               Grid& grid, double margin, std::vector<std::pair<int, int>>& pairs) {
  const std::size_t m = grid.order.size();
  std::vector<Vec3>& sortedLo = grid.sortedLo;
  std::vector<Vec3>& sortedHi = grid.sortedHi;
  std::vector<char>& sortedImmovable = grid.sortedImmovable;
  sortedLo.resize(m);
  sortedHi.resize(m);
  sortedImmovable.resize(m);
  for (std::size_t p = 0; p < m; ++p) {
    const int body = grid.order[p];
    sortedLo[p] = lo[body];
    sortedHi[p] = hi[body];
    sortedImmovable[p] = static_cast<char>(world.bodies[body].immovable);
  }
  const auto test = [&](int p, int q) {
    if (sortedImmovable[p] && sortedImmovable[q]) return;
    if (boundsWithin(sortedLo[p], sortedHi[p], sortedLo[q], sortedHi[q], margin)) {
      const int a = grid.order[p], b = grid.order[q];
      pairs.emplace_back(std::min(a, b), std::max(a, b));
    }
  };
  // Cells holding a movable body: two cells of immovable bodies alone (sleepers of a settled
  // pile, §4.5) pair nothing, and are not looked into.
  std::vector<char>& movableIn = grid.movableIn;
  movableIn.assign(grid.start.size(), 0);
  for (std::size_t p = 0; p < m; ++p)
    if (!sortedImmovable[p]) movableIn[static_cast<std::size_t>(grid.cell[p])] = 1;
  const Eigen::Vector3i& d = grid.dims;
  for (int begin = 0; begin < static_cast<int>(m);) {
    // The run of bodies in one cell: order[begin, end). Read from the body, not found by
    // walking the cells: a scattered scene has up to kGridCellsPerBody empty cells a body.
    const int c = grid.cell[begin];
    const int end = grid.start[c + 1];
    const int x = c % d.x(), y = (c / d.x()) % d.y(), z = c / (d.x() * d.y());
    const bool movableHere = movableIn[static_cast<std::size_t>(c)];
    if (movableHere)
      for (int p = begin; p < end; ++p)
        for (int q = p + 1; q < end; ++q) test(p, q);
    for (int dz = 0; dz <= 1; ++dz)
      for (int dy = dz == 0 ? 0 : -1; dy <= 1; ++dy)
        for (int dx = (dz == 0 && dy == 0) ? 1 : -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy, nz = z + dz;
          if (nx < 0 || ny < 0 || nx >= d.x() || ny >= d.y() || nz >= d.z()) continue;
          const int o = (nz * d.y() + ny) * d.x() + nx;
          if (!movableHere && !movableIn[static_cast<std::size_t>(o)]) continue;
          for (int q = grid.start[o]; q < grid.start[o + 1]; ++q)
            for (int p = begin; p < end; ++p) test(p, q);
        }
    begin = end;
  }
  widePairs(world, lo, hi, grid, margin, pairs);
}
}  // namespace

std::vector<std::pair<int, int>> sweepAndPrunePairs(const World& world, double margin,
                                                    const std::vector<double>& growth) {
  const int n = static_cast<int>(world.bodies.size());
  std::vector<Vec3> lo(n), hi(n);
  for (int i = 0; i < n; ++i)
    obbBounds(Obb::of(world.bodies[i]), growth.empty() ? 0.0 : growth[i], lo[i], hi[i]);
  return sweepAndPrunePairs(world, lo, hi, margin);
}

std::vector<std::pair<int, int>> sweepAndPrunePairs(const World& world,
                                                    const std::vector<Vec3>& lo,
                                                    const std::vector<Vec3>& hi, double margin) {
  SweepAndPrune sweep;
  std::vector<std::pair<int, int>> pairs;
  sweep.pairs(world, lo, hi, margin, pairs);
  return pairs;
}

/// The working lists of SweepAndPrune::pairs, kept for their room.
struct SweepAndPrune::Lists {
  std::vector<int> direct;                       ///< bodies tested directly
  std::vector<int> swept;                        ///< bodies swept or gridded
  std::vector<char> isDirect;                    ///< per body: tested directly
  std::vector<Interval> intervals;               ///< the sweep's intervals
  std::vector<Vec3> sortedLo;                    ///< the bounds in sweep order, m
  std::vector<Vec3> sortedHi;                    ///< the bounds in sweep order, m
  Grid grid;                                     ///< the uniform grid and its lists
  std::vector<std::pair<int, int>> sortedPairs;  ///< sortPairs' second list
  std::vector<std::size_t> start;                ///< sortPairs' counts
};

SweepAndPrune::SweepAndPrune() : lists_(std::make_unique<Lists>()) {}
SweepAndPrune::~SweepAndPrune() = default;
SweepAndPrune::SweepAndPrune(SweepAndPrune&&) noexcept = default;
SweepAndPrune& SweepAndPrune::operator=(SweepAndPrune&&) noexcept = default;
SweepAndPrune::SweepAndPrune(const SweepAndPrune&) : SweepAndPrune() {}
SweepAndPrune& SweepAndPrune::operator=(const SweepAndPrune&) { return *this; }

void SweepAndPrune::pairs(const World& world, const std::vector<Vec3>& lo,
                          const std::vector<Vec3>& hi, double margin,
                          std::vector<std::pair<int, int>>& pairs) {
  const int n = static_cast<int>(world.bodies.size());
  if (lo.size() != world.bodies.size() || hi.size() != world.bodies.size())
    throw std::invalid_argument("sweepAndPrunePairs: give one pair of bounds per body");
  Lists& w = *lists_;

  // A ground as wide as the scene, swept, would overlap every interval along the sweep axis and
  // make the sweep quadratic: immovable bodies much larger than every movable one are tested
  // directly. Sleeping bodies standing in as immovable (§4.5) are box-sized and many, so they
  // are swept: tested directly, they made the sweep quadratic in the number of sleepers. Bounds
  // that are not finite (a state gone to NaN) cannot be sorted, so they are tested directly
  // too, which keeps the result equal to the all-pairs one even then.
  double largestMovable = 0.0;
  for (const RigidBody& b : world.bodies)
    if (!b.immovable) largestMovable = std::max(largestMovable, b.halfExtents.maxCoeff());
  w.direct.clear();
  w.swept.clear();
  w.isDirect.assign(static_cast<std::size_t>(n), 0);
  for (int i = 0; i < n; ++i) {
    const RigidBody& b = world.bodies[i];
    const bool huge = b.immovable && !(b.halfExtents.maxCoeff() <= kSweptSizeRatio * largestMovable);
    w.isDirect[i] = huge || !lo[i].allFinite() || !hi[i].allFinite();
    (w.isDirect[i] ? w.direct : w.swept).push_back(i);
  }

  // Bodies resting in a stack touch a handful of neighbours each, so 4 n pairs is usually
  // room enough for all of them from the start (it is only a starting capacity).
  pairs.clear();
  pairs.reserve(4 * static_cast<std::size_t>(n));
  if (w.swept.size() >= kGridMinBodies &&
      buildGrid(lo, hi, w.swept, margin, w.direct, w.isDirect, w.grid))
    gridPairs(world, lo, hi, w.grid, margin, pairs);
  else
    sweepPairs(world, lo, hi, w.swept, margin, pairs, w.intervals, w.sortedLo, w.sortedHi);
  // After the grid: it may have moved outsized bodies to the directly tested ones.
  testDirect(world, lo, hi, w.direct, w.isDirect, margin, pairs);
  sortPairs(pairs, n, w.sortedPairs, w.start);
}

}  // namespace boxsim
