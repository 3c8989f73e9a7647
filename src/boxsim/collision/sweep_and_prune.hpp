/// \file
/// Sweep and prune: the broad phase for scenes larger than the thesis' own. \thesis{§4.1}
/// used no spatial subdivision because its scenes were small, and names subdivision a
/// necessity for larger ones; sweep and prune (Baraff's thesis, 1992, §6.2; Cohen, Lin,
/// Manocha and Ponamgi, I-COLLIDE, 1995) is the simplest such structure for boxes that are
/// all of similar size. It returns exactly the pairs of the all-pairs test, in the same order.
#pragma once

#include <memory>
#include <utility>
#include <vector>

#include "boxsim/core/world.hpp"

namespace boxsim {

/// The candidate pairs of candidatePairs(world, margin) for BroadPhase::AllPairs, found by
/// sorting instead of testing every pair: all index pairs (i, j), i < j, not both immovable,
/// whose axis-aligned bounds (obbBounds with margin 0) are at most `margin` (m) apart along
/// every world axis (touching bounds count), in increasing (i, j) order. The same list,
/// element for element, for every finite or non-finite state, because each reported pair
/// passes the very same floating-point test the all-pairs loop applies.
///
/// Method: the movable bodies' bounds are sorted by their lower end along the world axis
/// on which their centres spread most (ties by body index, so the order is total and the
/// same on every run), and each is compared only with those that follow it in that order
/// until their lower end lies beyond its upper end plus margin. Immovable bodies are tested
/// directly against every other body when they are much larger than every movable body (a
/// ground spans the whole scene, so sweeping it would make it overlap everything along the
/// sweep axis); box-sized immovable bodies, such as sleeping bodies standing in as immovable,
/// are swept. Pairs of two immovable bodies are never reported.
///
/// `growth`, when not empty, holds one length per body (m, >= 0): body i's bounds are grown by
/// growth[i] on every side before the margin test, so a pair is reported when its grown bounds
/// come within `margin`. Contact gathering uses it to widen each body by how far it can move.
///
/// From 64 swept bodies on, a uniform grid takes the sweep's place when it is dense enough
/// (at most 8 cells per body): each body goes into the cell of the lower corner of its bounds,
/// cells are as wide as the gridded bounds plus the margin, and each cell is compared with
/// itself and its 13 following neighbours. The cells are sized for 95 % of the bodies: the
/// widest 5 % (a fast body's swept bounds) look into every cell they can reach and are swept
/// among themselves, so a few wide bounds do not make every cell wide (the collapsing clump of
/// 10 000 cubes: 14 % fewer instructions than cells sized for the widest). Bodies more than 4
/// times the median extent are tested directly, against every body.
///
/// Complexity: O(n log n + s + m n + k) time and O(n + k) memory for n bodies, m of them
/// tested directly, k reported pairs and s >= k pairs of movable bodies that overlap along the
/// sweep axis only; O(n log n + k) for the usual few immovable bodies and scattered scenes,
/// against the all-pairs test's O(n²). A regular grid is the sweep's worst case: every box of
/// a slab across the sweep axis overlaps the rest of its slab along that axis, so s is about
/// n^{5/3}/2 for the clump of \thesis{Fig. 6.7} at its start; the uniform grid makes that case
/// O(n + k) (10 000 cubes at the start: 3.1 ms a call against 13 ms swept). Each call
/// sorts afresh (no state is kept between calls), so calls are independent and may run
/// concurrently.
std::vector<std::pair<int, int>> sweepAndPrunePairs(const World& world, double margin = 0.0,
                                                    const std::vector<double>& growth = {});

/// sweepAndPrunePairs with the bounds given: body i's world axis-aligned bounds are
/// [lo[i], hi[i]] (m), whatever they enclose (a body swept along its motion, say). The same
/// pairs as the all-pairs loop with boundsWithin(lo[i], hi[i], lo[j], hi[j], margin), not both
/// immovable, in increasing (i, j) order. Which bodies are swept, gridded or tested directly
/// is decided as above, from these bounds and the bodies' half extents.
/// \throws std::invalid_argument unless lo and hi hold one entry per body
std::vector<std::pair<int, int>> sweepAndPrunePairs(const World& world,
                                                    const std::vector<Vec3>& lo,
                                                    const std::vector<Vec3>& hi, double margin);

/// sweepAndPrunePairs with its working lists (the sort, the grid, the pairs' reordering) kept
/// from call to call: a caller that asks every step allocates nothing once the lists have
/// grown to the scene. A copy starts with empty lists of its own.
class SweepAndPrune {
 public:
  SweepAndPrune();
  ~SweepAndPrune();
  SweepAndPrune(SweepAndPrune&&) noexcept;             ///< takes the lists
  SweepAndPrune& operator=(SweepAndPrune&&) noexcept;  ///< takes the lists
  SweepAndPrune(const SweepAndPrune&);                 ///< empty lists of its own
  SweepAndPrune& operator=(const SweepAndPrune&);      ///< keeps its own lists
  /// `pairs` = sweepAndPrunePairs(world, lo, hi, margin), written over what it held.
  /// \throws std::invalid_argument unless lo and hi hold one entry per body
  void pairs(const World& world, const std::vector<Vec3>& lo, const std::vector<Vec3>& hi,
             double margin, std::vector<std::pair<int, int>>& pairs);

 private:
  struct Lists;                   ///< the working lists (sweep_and_prune.cpp)
  std::unique_ptr<Lists> lists_;
};

}  // namespace boxsim
