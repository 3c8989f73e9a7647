/// \file
/// The step's candidate pairs of the once-per-step gathering (once_per_step_gathering.hpp):
/// every body's bounds swept along its way in a pass, one sweep over them per step, the bodies
/// that outgrow their swept bounds in a pass tested again, and the pairs FIXCONTACTCONSTRAINTS
/// (\alg{DAMPEDINTEGRATION L5}) takes from the sweep. Only speed depends on the constants of the .cpp: every
/// pair a pass looks at still passes the broad phase's own test (boundsWithin) at that pass'
/// poses.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "boxsim/collision/separating_axis.hpp"
#include "boxsim/collision/sweep_and_prune.hpp"
#include "boxsim/core/world.hpp"
#include "boxsim/impulse_damped/contact_normal.hpp"
#include "boxsim/impulse_damped/slow_pair_cache.hpp"
#include "boxsim/impulse_damped/step_bodies.hpp"

namespace boxsim {

/// m: the rounding allowance of a bounds test on a body at x with half diagonal ρ (m): bounds
/// computed at two poses differ from the exact motion by rounding of order |x| + ρ.
double boundsRoundingSlack(const RigidBody& body, double halfDiagonal);

/// The pairs that may come within the margin during a step.
class StepCandidates {
 public:
  /// A pair that may come within the margin during the step, with the axis of its last test
  /// (separatedBeyond) and that test's answer, kept from sweep to sweep and step to step while
  /// the pair stays a candidate.
  struct Candidate {
    int a;                      ///< body index, a < b
    int b;                      ///< body index
    SeparatingAxisResult axis;  ///< kind and indices of the last test's axis
    bool apart;                 ///< the last test found no contact within the margin
    /// The pose (PassPoses::stamp) a stood at in the pass that last looked at the pair; 0:
    /// never looked at. When a's and b's are the same in a later pass, so is the answer.
    std::uint64_t stampA = 0;
    std::uint64_t stampB = 0;  ///< the same for b
    /// The manifold found then (index into the gathering's list), or -1: no contact within
    /// the margin.
    int manifold = -1;
    /// The pair's entry in the slow-pair cache, or -1: not cached.
    int cached = -1;
    /// The pair's places in the normal model's tables of faces, for its contacts in the passes.
    ContactNormalTracker::FacePlaces faces{};
    /// Gathered as a pair with a fast body in every pass although both are slow
    /// (ImpulseParams::exactEdgePairs): its cached manifold would have been edge-edge or empty.
    bool exactEach = false;
  };

  /// `slowWidening`: ImpulseParams::slowWidening; each body's swept bounds hold its bounds
  /// widened by it, so the slow pairs come from the candidates too.
  explicit StepCandidates(double slowWidening = 0.0) : slowWidening_(slowWidening) {}

  /// The step's first sweep, at the current poses, with `sweepMargin` (m) and the swept
  /// bounds at their normal stretch; candidates that are cached pairs of `cached` are linked
  /// to them (Candidate::cached).
  void start(const World& world, const StepBodies& bodies, const std::vector<PairReach>& cached,
             const Vec3& gravityStep, double dt, double sweepMargin, StampCounter& stamps);
  /// Gives the `outgrown` bodies swept bounds for their current velocities and adds the
  /// candidates that brings (bodies at their current poses); many at once, and the whole sweep
  /// is redone with every body's stretch doubled for the rest of the step.
  void grow(const World& world, const StepBodies& bodies, const std::vector<PairReach>& cached,
            const Vec3& gravityStep, double dt, const std::vector<int>& outgrown,
            StampCounter& stamps);
  /// Whether body i, moved by `displacement` (m) and turned so that no corner moves more than
  /// `turn` (m), stays inside its swept bounds.
  bool withinSweptBounds(const RigidBody& body, int i, const StepBodies& bodies,
                         const Vec3& displacement, double turn) const;
  /// candidatePairs(world, margin) for the bodies where they stand now, from the candidates: a
  /// pair of bodies inside their swept bounds is a candidate if it passes the test at all, and
  /// the few bodies outside theirs are tested against every body. False, `pairs` untouched,
  /// when the candidates cannot tell: a margin wider than the sweep's, another number of
  /// bodies, or many bodies outside their swept bounds.
  bool pairsAt(const World& world, double margin, std::vector<std::pair<int, int>>& pairs) const;

  /// The sweep's pairs in increasing (a, b) order, then those grow() added since, in the order
  /// it added them.
  std::vector<Candidate>& candidates() { return candidates_; }
  /// Lists each body's candidates for ofBody(), unless listed already for these candidates
  /// (the same sweep and count); `n` bodies.
  void indexByBody(std::size_t n);
  /// Body i's candidates, as indices into candidates() in increasing order, as indexByBody()
  /// last listed them.
  std::span<const int> ofBody(int i) const {
    const auto first = static_cast<std::size_t>(byBodyStart_[static_cast<std::size_t>(i)]);
    const auto last = static_cast<std::size_t>(byBodyStart_[static_cast<std::size_t>(i) + 1]);
    return {byBody_.data() + first, last - first};
  }
  /// Whether body i is in at least one candidate pair.
  bool hasCandidate(int i) const { return hasCandidate_[i] != 0; }
  /// Whether grow() added pairs since the last sweep (the candidates are then out of order).
  bool grown() const { return !grownKeys_.empty(); }
  /// A stamp of body i's swept bounds, new each time they are set.
  std::uint64_t sweptStamp(int i) const { return sweptStamp_[i]; }
  /// Sweeps so far, for noticing a new one.
  std::uint64_t sweeps() const { return sweeps_; }
  /// m: the margin the sweep ran with.
  double sweepMargin() const { return sweepMargin_; }

 private:
  /// The bodies' swept bounds sorted along x, so grow() finds a body's neighbours by one
  /// binary search and a scan of a slab instead of testing every body. Sorted when first
  /// needed after a sweep; bounds set again since are listed in `regrown` and tested directly,
  /// as are the bodies in `direct`.
  struct SweptIndex {
    bool valid = false;
    std::uint64_t stamp = 0;   ///< the last stamp when sorted: sweptStamp_ above it is newer
    std::vector<int> order;    ///< bodies by sweptLo_.x
    std::vector<double> lo;    ///< m, sweptLo_.x in that order
    std::vector<double> maxHi; ///< m, the largest sweptHi_.x up to each place in that order
    std::vector<int> direct;   ///< wide immovable bodies and bounds that are not finite
    std::vector<int> regrown;  ///< bodies whose bounds were set again since the sort
  };

  /// One sweep over every body's swept bounds, with sweepMargin_; bodies at their current poses.
  void sweep(const World& world, const StepBodies& bodies, const std::vector<PairReach>& cached,
             const Vec3& gravityStep, double dt, StampCounter& stamps);
  /// Sets body i's swept bounds from its current pose and velocities: its bounds stretched
  /// along kSweptStretch times its displacement in a pass and grown sideways, holding its
  /// bounds grown by the slow widening.
  void setSweptBounds(const World& world, const StepBodies& bodies, int i,
                      const Vec3& gravityStep, double dt, StampCounter& stamps);
  /// Sorts the swept bounds into index_.
  void indexSweptBounds(const World& world, const StampCounter& stamps);
  /// Calls visit(j) for every body j whose swept bounds may lie within `margin` (m) of
  /// [lo, hi] (m) along every axis, from index_: a superset of the bodies boundsWithin
  /// passes, some perhaps twice, never one it fails along x.
  template <class Visit>
  void forSweptBoundsNear(const Vec3& lo, const Vec3& hi, double margin, const Visit& visit) const;

  double slowWidening_;
  double sweepMargin_ = 0.0;  ///< m, the margin of the sweep
  double stretch_ = 1.0;      ///< this step's stretch of the swept bounds, times kSweptStretch
  std::vector<Candidate> candidates_;
  /// The candidates before the last sweep, by pair: where a pair that is a candidate again
  /// finds the axis of its last test (Candidate::axis, apart).
  std::vector<Candidate> previous_;
  std::vector<std::pair<int, int>> sweptKeys_;  ///< the sweep's pairs: candidates_ up to its size
  std::vector<std::pair<int, int>> grownKeys_;  ///< the pairs added since, sorted (empty: none)
  std::vector<Vec3> sweptLo_, sweptHi_;         ///< m, per body: its swept bounds
  std::vector<std::uint64_t> sweptStamp_;       ///< per body: a new stamp each time they are set
  SweptIndex index_;                            ///< sweptLo_, sweptHi_ sorted (grow)
  std::vector<char> hasCandidate_;              ///< per body: in at least one candidate pair
  /// indexByBody(): body i's candidates are byBody_[byBodyStart_[i] .. byBodyStart_[i + 1]),
  /// listed for the sweep byBodySweep_ with byBodyCount_ candidates.
  std::vector<int> byBody_;
  std::vector<int> byBodyStart_;
  std::vector<int> byBodyFill_;  ///< indexByBody's cursors
  std::uint64_t byBodySweep_ = 0;
  std::size_t byBodyCount_ = 0;
  std::vector<char> isOutgrown_;                ///< per body, in grow(): among the outgrown
  std::vector<std::pair<int, int>> found_;      ///< grow()'s new pairs
  SweepAndPrune sweepAndPrune_;                 ///< the sweep's working lists
  /// pairsAt's working lists: per body its bounds now and whether they left the swept ones;
  /// the bodies that did.
  mutable std::vector<Vec3> nowLo_, nowHi_;
  mutable std::vector<char> outside_;
  mutable std::vector<int> outsiders_;
  std::uint64_t sweeps_ = 0;                    ///< sweeps so far
};

}  // namespace boxsim
