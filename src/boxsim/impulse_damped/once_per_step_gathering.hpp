/// \file
/// The once-per-step gathering (ContactGatheringMode::OncePerStep, the default): the contacts
/// gatherCollisions finds at the predicted poses in each pass of RESOLVECOLLISIONS and
/// RESOLVECONTACTS (\alg{RESOLVECOLLISIONS L2-L3}, \alg{RESOLVECONTACTS L2-L3}), found mostly once per step. Bodies are slow or fast by
/// their reach in a pass, Δt (|v'| + |ω| ρ) with ρ the half diagonal, against
/// ImpulseParams::exactReach. Its parts:
///
/// - **Slow pairs** (slow_pair_cache.hpp): pairs of two slow bodies get one narrow phase per
///   step at the current poses, each body's margin widened by ImpulseParams::slowWidening (more
///   than a slow body can move); every pass then leaves them where they are and predicts the
///   depth of each cached contact point at the predicted poses by a Taylor expansion in the
///   displacement:
///
///       depth' = depth + n · (d_a(p) - d_b(p)),
///       d(p) = Δt (v' + ω × r) + ½ Δt² ω × (ω × r),   r = p - x,
///
///   exact for translation and off by O(Δt³ |ω|³ ρ / 6) for rotation, below 1e-7 ℓ under the
///   default exactReach. A contact joins the pass when one of its points has depth' > -margin,
///   the criterion of the as-written gathering; its point is the mean of those points.
/// - **Pairs with a fast body**, as written. Fast bodies move to their predicted poses
///   (pass_poses.hpp) and a broad and narrow phase at those poses finds their contacts, every
///   pass. The broad phase of a pass returns what the world's broad phase (candidatePairs)
///   would at those poses, found faster: the step's candidates (step_candidates.hpp), one
///   sweep per step over every movable body's bounds swept along its way in a pass, list the
///   pairs that can come near in the step, and each pass applies the broad phase's own test
///   (boundsWithin at the pass' poses) to that list alone. A body whose predicted bounds would
///   leave its swept ones (an impulse turned or sped it up) gets new ones and is tested against
///   the bodies near them. A fast body in no candidate pair touches nothing in the step, so it
///   is not moved at all. The narrow phase of a pair that was apart in its last test, in this
///   step or an earlier one while it stayed a candidate, first looks along the axis that
///   separated it (separatedBeyond), which decides most pairs of a flying clump with one axis
///   instead of fifteen, and always as the full test would.
/// - **A fast body's slow partners**: every slow body whose bounds come within the margin plus
///   its own reach in the pass of a moved fast body's moves to its predicted pose too, so the
///   narrow phase of the pair sees both bodies where \alg{A.2} puts them and finds the contact
///   the as-written gathering finds. Left where it stands, the partner would be off by up to
///   exactReach ℓ, far more than the margin (10⁻³ of the smallest ℓ): a thin plate, fast under
///   gravity alone for its small ℓ, moves down g Δt² in every pass under a resting box that
///   stays, and their contact would never be seen (regression test "A slow box on a fast thin
///   plate is gathered as every-pass gathering finds it", contact_gathering_test.cpp). The partners go back to their current poses
///   before COLLIDE, with velocities recomputed exactly as they were, so the slow pairs'
///   prediction and the impulses see every slow body in one place.
/// - **Pairs moving together** (ImpulseParams::pairReach): a pair with a fast body whose two
///   bodies move together, Δt |v'_a - v'_b| plus both turns Δt |ω| ρ within exactReach ℓ of the
///   smaller, is cached and predicted as a slow pair is, if its narrow phase at the current
///   poses has points. The prediction is exact for any translation the two share, so its error
///   is bounded by their relative motion, not their speed: the cubes of a clump flying on
///   together after they meet are predicted, not looked at in every pass. A pair that stops
///   moving together in a pass (an impulse parted them) is gathered as written in that pass.
/// - **Settled islands** (contact_islands.hpp): the bodies of an island of candidate pairs that
///   settled sit the pass out; they would stand, move and touch as in the pass that settled them.
///
/// Contacts of both kinds are ordered by pair, as the as-written gathering orders them.
/// Speculative contacts (Catto, "Speculative Contacts", GDC 2013) make the same first-order
/// prediction. On a resting stack every body is slow and a step costs one narrow phase instead
/// of one per pass (16 with the default iterations); in an impact the fast bodies cost what
/// they cost as written.
///
/// DEVIATION(RESOLVECOLLISIONS L2-L3, RESOLVECONTACTS L2-L3): slow bodies, and fast pairs
/// moving together, are not moved to their predicted poses. The cache is rebuilt when a body's
/// mobility changes (a sleeping body wakes, \thesis{§4.5}) and every step. A fast body's slow
/// partner is moved only for the narrow phase of its pairs with fast bodies. What differs from
/// the as-written gathering: a slow pair's depth by the rotation error above; the lever arm of
/// an impulse in a slow pair by at most its bodies' reach (exactReach ℓ, 1 % of a box's size
/// by default); and a slow pair's manifold points, which stay those found at the current pose.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "boxsim/collision/contact.hpp"
#include "boxsim/core/world.hpp"
#include "boxsim/impulse_damped/contact_islands.hpp"
#include "boxsim/impulse_damped/contact_normal.hpp"
#include "boxsim/impulse_damped/impulse_params.hpp"
#include "boxsim/impulse_damped/parallel_for.hpp"
#include "boxsim/impulse_damped/pass_poses.hpp"
#include "boxsim/impulse_damped/slow_pair_cache.hpp"
#include "boxsim/impulse_damped/step_bodies.hpp"
#include "boxsim/impulse_damped/step_candidates.hpp"

namespace boxsim {

/// gatherCollisions of the passes of a step, found mostly once per step (the file comment).
/// ContactGathering runs it; use: gather() for every pass, endPass() after it, endStep() once
/// per step.
class OncePerStepGathering {
 public:
  /// A gathering with the reach, widening and pair-reach settings of `params`.
  explicit OncePerStepGathering(const ImpulseParams& params);

  /// The step's candidates and slow pairs at the current poses (ContactGathering::beginStep),
  /// unless those of this step still hold for `margin` (m) and the bodies' mobility.
  void beginStep(const World& world, const Vec3& gravityStep, double dt, double margin,
                 ContactNormalTracker& normals);
  /// RESOLVECOLLISIONS / RESOLVECONTACTS L2-L3 of a pass, predicting with v' = v + `gravityStep` (m/s) over dt (s):
  /// `contacts` gets every pair closer than `margin` (m), one ImpulseContact per pair in
  /// increasing (a, b) order, with the lever arms of the poses it was found at; every body is
  /// back at its pose when this returns.
  void gather(World& world, const Vec3& gravityStep, double dt, double margin,
              ContactNormalTracker& normals, std::vector<ImpulseContact>& contacts);
  /// Ends a pass.
  void endPass() { poses_.endPass(); }
  /// Ends the step: the cache is dropped (the step moves the bodies); the kept narrow phases
  /// of the pairs the step asked about stay (KeptNarrowPhase::endStep).
  void endStep() {
    cached_ = false;
    bodies_.endStep();
    kept_.endStep();
  }
  /// The narrow phases of the step, kept for the poses they were run at: the cache's builds
  /// run through it, and so may the caller's own (FIXCONTACTCONSTRAINTS).
  KeptNarrowPhase& kept() { return kept_; }
  /// As kept(), read only.
  const KeptNarrowPhase& kept() const { return kept_; }
  /// ContactGathering::stepPairs.
  bool stepPairs(const World& world, double margin, std::vector<std::pair<int, int>>& pairs) const;
  /// The islands of the step's candidate pairs, kept up to date pass by pass.
  ContactIslands& islands() { return islands_; }
  /// The bodies that stand in as immovable but may wake within a pass (one flag per body, as
  /// Sleeping::asleep(); null: none), read whenever the islands are built: they count as
  /// movable there and join their partners' islands (contact_islands.hpp). The vector must
  /// outlive the step.
  void setSleepers(const std::vector<char>* asleep) { sleepers_ = asleep; }
  /// With a predicted anchor (ImpulseParams::predictedAnchor): the bodies touching another at
  /// the step's start, one flag per body, or null (or another size): every body fast at the
  /// start is anchored where the first pass predicts it. Given, only those that touch are: a
  /// free-flying body has no contact for the passes to predict, and its pairs are found as
  /// they come near, as without the anchor. The pointer must stay valid while steps run.
  void setTouching(const std::vector<char>* touching) { touching_ = touching; }
  /// Where the shared narrow phases' work is measured (ParallelWork), or null: none. While
  /// measured, every pass plans its pairs before their narrow phases, on one thread too.
  void setParallelWork(ParallelWork* work);

  /// Builds of the cache since construction (one narrow phase of the slow pairs each).
  long narrowPhases() const { return narrowPhases_; }
  /// Separating-axis tests of pairs with a fast body at the poses of a pass, since construction.
  long passNarrowPhases() const { return passNarrowPhases_; }
  /// One-axis checks (separatedBeyond) that answered for such a test, since construction: a
  /// pair apart in its last pass and still apart along the axis that parted it.
  long passAxisChecks() const { return passAxisChecks_; }
  /// Bodies that sat a pass out because their island was settled, summed over the passes.
  long skippedBodyPasses() const { return skippedBodyPasses_; }
  /// Passes whose narrow phases of pairs with a fast body ran on several threads.
  long parallelTestPasses() const { return parallelTestPasses_; }

 private:
  /// What a pass works out from a body's velocities before moving it: its reach and whether
  /// its predicted bounds stay inside its swept bounds, kept while v and ω stay bitwise the same.
  struct PassMotion {
    Vec3 v, omega;            ///< the key
    double reach = 0.0;       ///< m, Δt (|v'| + |ω| ρ)
    double turn = 0.0;        ///< m, Δt |ω| ρ
    bool withinSwept = false; ///< withinSweptBounds' answer for the bounds of sweptStamp
    std::uint64_t sweptStamp = 0;  ///< the swept bounds asked about; 0: not asked
    std::uint64_t stamp = 0;  ///< valid when greater than buildStamp_
  };

  /// A pair with a fast body in a pass, between planFastPair and finishFastPair.
  struct FastPairTask {
    int k = -1;         ///< the candidate
    int manifold = -1;  ///< test < 0: the index of its cached manifold in manifolds_
    int test = -1;      ///< its narrow phase's slot in fastTested_, or -1: cached
    bool axisChecked = false;  ///< the last separating axis answered (no full test)
    bool touching = false;     ///< the narrow phase's answer
  };

  /// Whether the cache was built for `margin` and bodies of the mobility the world's have now.
  bool cacheCovers(const World& world, double margin) const;
  /// The step's bodies, candidates and slow pairs at the current poses.
  void buildCache(const World& world, const Vec3& gravityStep, double dt, double margin,
                  ContactNormalTracker& normals);
  /// Sorts the bodies of this pass: settled islands sit it out (skip_), the others are slow or
  /// fast (fastThisPass_), and the candidates grow for the fast ones that outgrew their swept
  /// bounds.
  void sortBodies(const World& world, const Vec3& gravityStep, double dt);
  /// Movable body i's reach in this pass (passReach_); if fast, listed in fastThisPass_, and in
  /// outgrown_ when its predicted bounds leave its swept bounds.
  void classify(const World& world, std::size_t i, const Vec3& gravityStep, double dt);
  /// Brings the islands up to the step's candidates and cached pairs: built anew after a sweep
  /// (a sleeper that wakes changes the bodies' mobility, and gather() then builds the cache and
  /// sweeps anew), joined with the pairs added since otherwise.
  void refreshIslands(const World& world);
  /// RESOLVECOLLISIONS / RESOLVECONTACTS L2-L3 for the pairs with a fast body, as written: the contacts of the pass'
  /// fast bodies and their slow partners at their predicted poses, into fastContacts_ in
  /// (a, b) order. The bodies that touch are moved there (putBackAll() returns them). Each pair
  /// is planned (planFastPair), tested (candidateManifold) and finished (finishFastPair); on
  /// one thread pair by pair, on several in three rounds, every pair planned in order, then
  /// their narrow phases together (testFastPairs), then every pair finished in order; on
  /// several threads too pair by pair when the last pass had fewer narrow phases than
  /// ImpulseParams::parallelNarrowPhases (and the work is not measured).
  void gatherFastPairs(World& world, const Vec3& gravityStep, double dt, double margin,
                       ContactNormalTracker& normals);
  /// The fast pair of candidate k at the pass' poses, up to its narrow phase: stands its slow
  /// partner, and says in `task` whether the pair's cached manifold is its answer (test < 0) or
  /// a narrow phase has to run (test 0); false when the pair has no contact (or is predicted
  /// with the cached pairs). One of its bodies must stand fast at its predicted pose
  /// (PassPoses::fastAtPredicted), or the pair be gathered exactly although slow
  /// (Candidate::exactEach; then both are stood there).
  bool planFastPair(const World& world, std::size_t k, const Vec3& gravityStep, double dt,
                    double margin, FastPairTask& task);
  /// The narrow phases planFastPair listed, each into its own slot of fastTested_; on several
  /// threads when ImpulseParams::threads > 1 and there are ImpulseParams::parallelNarrowPhases
  /// of them.
  void testFastPairs(const World& world, double margin);
  /// The rest of a listed pair, in the planned order: its manifold kept (`tested`, the narrow
  /// phase's, when it had one), both bodies moved to where the pass predicts them, and its
  /// contact into fastContacts_.
  void finishFastPair(World& world, const FastPairTask& task, const ContactManifold& tested,
                      ContactNormalTracker& normals);
  /// The narrow phase of the task's candidate where its bodies stand in the pass, trying its
  /// last separating axis first and remembering the axis of this test; false (manifold left as
  /// it was) when they do not touch within the margin. Writes only the candidate, the task and
  /// `manifold`.
  bool candidateManifold(const World& world, FastPairTask& task, double margin,
                         ContactManifold& manifold);
  /// The world the slow pairs are found and predicted in: the bodies at their anchors with a
  /// predicted anchor (anchorWorld_), else `world` itself.
  const World& cacheWorldOf(const World& world) const {
    return bodies_.anchored ? anchorWorld_ : world;
  }
  /// revertToOriginalPositions for the pass' partners and fast bodies, before COLLIDE.
  void putBackAll(World& world);
  /// The cached pairs' contacts of this pass merged with fastContacts_ in (a, b) order.
  void mergeSlowPairs(const World& world, double dt, double margin, ContactNormalTracker& normals,
                      std::vector<ImpulseContact>& contacts);

  ImpulseParams params_;
  StampCounter stamps_;
  /// The stamp of the current poses since the last build of the cache; predicted poses and
  /// pass motions with smaller stamps are from before it and invalid.
  std::uint64_t buildStamp_ = 0;
  Vec3 predictedGravity_ = Vec3::Zero();  ///< the g Δt and Δt the predicted poses are for
  double predictedDt_ = 0.0;
  bool cached_ = false;
  double cacheMargin_ = 0.0;  ///< m, the margin the cache was built for
  StepBodies bodies_;
  /// With a predicted anchor (ImpulseParams::predictedAnchor): the bodies at their anchors,
  /// where the slow pairs are found and predicted from (StepBodies::anchorVelocity).
  World anchorWorld_;
  StepCandidates candidates_;
  SlowPairCache slowPairs_;
  PassPoses poses_;
  std::vector<PassMotion> motion_;    ///< per body: its reach and swept-bounds test of the last pass
  std::vector<double> passReach_;     ///< m, per movable body: its reach in this pass
  std::vector<int> fastThisPass_;     ///< this pass: bodies fast now or at the cache's build
  std::vector<int> outgrown_;         ///< this pass: fast bodies that outgrew their swept bounds
  std::vector<ContactManifold> manifolds_;  ///< the candidates' last manifolds (Candidate::manifold)
  std::vector<ImpulseContact> fastContacts_;  ///< this pass: the pairs with a fast body, by pair
  std::vector<int> fastCandidates_;    ///< this pass: the candidates with a fast body, listed
  /// The candidates gathered exactly although slow (Candidate::exactEach), in candidate order.
  std::vector<int> exactCandidates_;
  std::uint64_t exactSweep_ = 0;  ///< the sweep exactCandidates_ numbers candidates of
  std::vector<FastPairTask> fastTasks_;       ///< this pass: planFastPair's list, in order
  std::vector<int> fastTests_;                ///< this pass: the tasks with a narrow phase
  std::vector<ContactManifold> fastTested_;   ///< per narrow phase of fastTests_: its manifold
  int lastPassTests_ = 0;  ///< narrow phases of pairs with a fast body in the last pass that had any
  ContactIslands islands_;            ///< the islands of the candidates (islands())
  KeptNarrowPhase kept_;              ///< the narrow phases of the step (kept())
  std::vector<int> batchCandidates_;  ///< buildCache: the candidate of each narrow phase of its batch
  std::uint64_t islandSweep_ = 0;     ///< the sweep islands_ was built after
  std::size_t joinedCandidates_ = 0;  ///< candidates joined into islands_ so far
  std::vector<char> skip_;            ///< per body, this pass: its island is settled
  std::vector<char> movable_;         ///< per body, refreshIslands(): movable, or a sleeper
  const std::vector<char>* sleepers_ = nullptr;  ///< setSleepers()
  const std::vector<char>* touching_ = nullptr;  ///< setTouching()
  ParallelWork* work_ = nullptr;                 ///< setParallelWork()
  bool anySkipped_ = false;           ///< this pass: some body's island is settled
  long narrowPhases_ = 0;
  long passNarrowPhases_ = 0;
  long passAxisChecks_ = 0;
  long skippedBodyPasses_ = 0;
  long parallelTestPasses_ = 0;
};

}  // namespace boxsim
