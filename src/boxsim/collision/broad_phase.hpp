/// \file
/// Candidate pairs for the narrow phase. \thesis{§4.1}: the thesis used no spatial
/// subdivision for its small scenes and names it a necessity for larger ones. Two broad
/// phases give the same pairs in the same fixed order: the thesis' all-pairs test with an
/// axis-aligned bounding box reject, and sweep and prune (sweep_and_prune.hpp), the default.
/// The world chooses (World::broadPhase, a BroadPhase); every query here follows its choice.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "boxsim/collision/contact.hpp"
#include "boxsim/collision/kept_narrow_phase.hpp"
#include "boxsim/collision/sweep_and_prune.hpp"
#include "boxsim/core/enum_names.hpp"
#include "boxsim/core/world.hpp"

namespace boxsim {

/// The name of a broad phase in scene files and on the command line: "all_pairs" or
/// "sweep_and_prune".
std::string broadPhaseName(BroadPhase kind);

/// The names of the broad phases.
inline constexpr EnumNames<BroadPhase, 2> kBroadPhaseNames{{
    {BroadPhase::AllPairs, "all_pairs"},
    {BroadPhase::SweepAndPrune, "sweep_and_prune"},
}};

/// The broad phase called `name` ("all_pairs" or "sweep_and_prune", as broadPhaseName gives).
/// Throws std::invalid_argument, listing the valid names, for any other name.
BroadPhase parseBroadPhase(const std::string& name);

/// World-space axis-aligned bounds of a box, grown by margin (m) on every side: the centre
/// plus or minus |R| h + margin, with R the box's axes and h its half extents (m). Exact: each
/// face of the bounds touches a corner of the box when margin = 0.
void obbBounds(const Obb& box, double margin, Vec3& lo, Vec3& hi);

/// The half widths of a box's bounds along the world axes, |R| h (m): what obbBounds adds to
/// the margin. Along world axis k it is sum_i |R_ki| h_i: each of the box's own axes
/// contributes its half extent times how far that axis leans along k.
inline Vec3 obbReach(const Obb& box) { return box.axes.cwiseAbs() * box.halfExtents; }

/// obbBounds of a box with centre `center` (m) and obbReach `reach` (m), grown by margin (m):
/// the same bits, for a caller that keeps the reach of a box it bounds with several margins.
inline void boundsAbout(const Vec3& center, const Vec3& reach, double margin, Vec3& lo, Vec3& hi) {
  const Vec3 grown = reach + Vec3::Constant(margin);
  lo = center - grown;
  hi = center + grown;
}

/// True when bounds [loA, hiA] and [loB, hiB] (m) are at most margin (m) apart along every
/// world axis; touching bounds (gap 0) count, so a box resting exactly on the ground is found
/// with margin 0. Symmetric in A and B. The one test both broad phases apply to a pair, which
/// is what makes their results equal bit for bit.
inline bool boundsWithin(const Vec3& loA, const Vec3& hiA, const Vec3& loB, const Vec3& hiB,
                         double margin) {
  for (int k = 0; k < 3; ++k)
    if (!(loB[k] - hiA[k] <= margin && loA[k] - hiB[k] <= margin)) return false;
  return true;
}

/// All index pairs (i, j), i < j, not both immovable, whose bounds (obbBounds with margin 0)
/// pass boundsWithin(margin) (m), in increasing (i, j) order, found by world.broadPhase.
/// Deterministic and the same list whichever broad phase the world names: AllPairs runs nested
/// loops over body indices in O(n²); SweepAndPrune (sweepAndPrunePairs) sorts in
/// O(n log n + k) for k pairs and returns the same list.
std::vector<std::pair<int, int>> candidatePairs(const World& world, double margin = 0.0);

/// candidatePairs with the bounds given: body i's world axis-aligned bounds are [lo[i], hi[i]]
/// (m), whatever they enclose (a body stretched along its motion, say). All index pairs (i, j),
/// i < j, not both immovable, with boundsWithin(lo[i], hi[i], lo[j], hi[j], margin), in
/// increasing (i, j) order, found by world.broadPhase: nested loops for AllPairs,
/// sweepAndPrunePairs(world, lo, hi, margin) for SweepAndPrune; the same list either way.
/// \throws std::invalid_argument unless lo and hi hold one entry per body
std::vector<std::pair<int, int>> candidatePairs(const World& world, const std::vector<Vec3>& lo,
                                                const std::vector<Vec3>& hi, double margin);

/// candidatePairs(world, lo, hi, margin) into `pairs` (written over), the sweep's working lists
/// kept in `sweep` from call to call: once they have grown to the scene, nothing is allocated.
/// \throws std::invalid_argument unless lo and hi hold one entry per body
void candidatePairs(const World& world, const std::vector<Vec3>& lo, const std::vector<Vec3>& hi,
                    double margin, SweepAndPrune& sweep, std::vector<std::pair<int, int>>& pairs);

/// Every pair of bodies whose manifold has at least one point (depth > -margin, m), with a and
/// b filled in, in increasing (a, b) order: collideBoxes on each of candidatePairs(world,
/// margin). The result does not depend on world.broadPhase. \thesis{§3.2}
std::vector<ContactManifold> findContacts(const World& world, double margin = 0.0);

/// findContacts with the broad phase's answer given: `pairs` must be candidatePairs(world,
/// margin) (found some cheaper way, as ContactGathering::stepPairs does); collideBoxes runs on
/// each. The same list as findContacts(world, margin). `kept`, when given, runs each narrow
/// phase (KeptNarrowPhase::collide), sparing the tests of pairs that stand as when last
/// tested; the same list. \thesis{§3.2}
std::vector<ContactManifold> findContacts(const World& world, double margin,
                                          const std::vector<std::pair<int, int>>& pairs,
                                          KeptNarrowPhase* kept = nullptr);

/// findContacts(world, margin, pairs, kept) into `contacts` (written over; its room kept).
void findContacts(const World& world, double margin, const std::vector<std::pair<int, int>>& pairs,
                  KeptNarrowPhase* kept, std::vector<ContactManifold>& contacts);

/// findContacts(world, margin) after only some bodies moved: `before` is what findContacts
/// returned with the same margin when every body stood where it stands now except those with
/// moved[i] != 0. The pairs of two bodies that did not move keep their manifolds (the same
/// poses give the same manifold, bit for bit); the broad and narrow phase run again for the
/// pairs with a moved body (found by world.broadPhase, or, for a few moved bodies, by testing
/// each against every body). The same list as findContacts(world, margin), element for
/// element, for the cost of at most a broad phase and the narrow phases of the moved bodies'
/// pairs.
/// \param moved  one entry per body
/// \param kept   when given, runs the narrow phases (KeptNarrowPhase::collide); the same list
/// \throws std::invalid_argument unless moved has one entry per body
std::vector<ContactManifold> refindContacts(const World& world, double margin,
                                            const std::vector<ContactManifold>& before,
                                            const std::vector<char>& moved,
                                            KeptNarrowPhase* kept = nullptr);

/// The working lists of refindContacts, kept by a caller that asks every step: once they have
/// grown to the scene, a call allocates nothing.
struct BroadPhaseLists {
  SweepAndPrune sweep;                     ///< the sweep's own lists
  std::vector<Vec3> lo;                    ///< per body, the lower corner of its bounds, m
  std::vector<Vec3> hi;                    ///< per body, the upper corner of its bounds, m
  std::vector<std::pair<int, int>> pairs;  ///< the pairs found
  std::vector<int> movedBodies;            ///< the bodies flagged moved
};

/// refindContacts(world, margin, before, moved, kept) into `contacts` (written over; not
/// `before`), with the working lists in `lists`. `pairs`, when given, is candidatePairs(world,
/// margin) at the poses the bodies stand at now, found some cheaper way (as
/// ContactGathering::stepPairs does): the pairs with a moved body are taken from it instead
/// of a broad phase; the same list.
/// \throws std::invalid_argument unless moved has one entry per body
void refindContacts(const World& world, double margin, const std::vector<ContactManifold>& before,
                    const std::vector<char>& moved, KeptNarrowPhase* kept, BroadPhaseLists& lists,
                    std::vector<ContactManifold>& contacts,
                    const std::vector<std::pair<int, int>>* pairs = nullptr);

/// The deepest overlap of any pair of bodies (separating-axis depth), m; 0 when none overlaps.
/// Pairs come from candidatePairs(world), so from world.broadPhase; the result does not depend
/// on it.
/// A measure for tests and figures (how far a technique lets boxes interpenetrate).
double deepestPenetration(const World& world);

/// True when bodies i and j overlap with a separating-axis depth above `tolerance` (m).
bool pairIntersects(const World& world, int i, int j, double tolerance);

/// Pairs a search for intersections passes over: true for (world, i, j) skips the pair i < j.
using PairFilter = std::function<bool(const World& world, int i, int j)>;

/// The first pair (in candidatePairs order) whose separating-axis depth exceeds `tolerance`
/// (m) and that `skip` (when set) does not skip, or (-1, -1) when none does. A negative
/// tolerance also reports pairs closer than -tolerance. The pairs come from candidatePairs, so
/// from world.broadPhase; the result does not depend on it.
std::pair<int, int> firstIntersectingPair(const World& world, double tolerance,
                                          const PairFilter& skip = {});

}  // namespace boxsim
