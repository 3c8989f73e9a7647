/// \file
/// gatherCollisions of RESOLVECOLLISIONS and RESOLVECONTACTS (\alg{A.2} L2-L3 and L6 of either):
/// the contacts between bodies moved to their predicted positions x + Δt v'. Two ways to find
/// them, chosen by ImpulseParams::gathering:
///
/// - EveryPass, \alg{A.2} as written (and Guendelman et al. 2003, §7): every pass moves each
///   body to its predicted pose, runs the broad and narrow phase there, and moves it back.
/// - OncePerStep, the default: bodies are slow or fast by their reach in a pass,
///   Δt (|v'| + |ω| ρ) with ρ the half diagonal, against ImpulseParams::exactReach.
///   - Pairs of two slow bodies: one narrow phase per step at the current poses, each body's
///     margin widened by ImpulseParams::slowWidening (more than a slow body can move); every
///     pass then leaves them where they are and predicts the depth of each cached contact point
///     at the predicted poses by a Taylor expansion in the displacement:
///
///         depth' = depth + n · (d_a(p) - d_b(p)),
///         d(p) = Δt (v' + ω × r) + ½ Δt² ω × (ω × r),   r = p - x,
///
///     exact for translation and off by O(Δt³ |ω|³ ρ / 6) for rotation, below 1e-7 ℓ under the
///     default exactReach. A contact joins the pass when one of its points has
///     depth' > -margin, the criterion of EveryPass; its point is the mean of those points.
///   - Pairs with a fast body: as written. Fast bodies move to their predicted poses and a broad
///     and narrow phase at those poses finds their contacts, every pass. The broad phase of a pass
///     returns what the world's broad phase (candidatePairs) would at those poses, found faster:
///     one broad phase per step, over every movable body's bounds stretched along its way in a pass
///     (kGuardFactor times it, grown sideways a little, and at least by the slow widening), lists
///     the pairs that can come near in the step; each pass applies the broad phase's own test
///     (boundsWithin at the pass' poses) to that list alone. A body whose predicted bounds would
///     leave its stretched ones (an impulse turned or sped it up) gets new ones and is tested
///     against the bodies whose stretched bounds, sorted along x, come near its new ones (or,
///     when many leave theirs at once, the broad phase is redone). A fast
///     body in no candidate pair touches nothing in the step, so it is not moved at all. The narrow
///     phase of a pair that was apart in its last pass first looks along the axis that separated it
///     (separatedBeyond), which decides most pairs of a flying clump with one axis instead of
///     fifteen, and always as the full test would.
///   - A fast body's slow partners: every slow body whose bounds come within the margin plus its
///     own reach in the pass of a moved fast body's moves to its predicted pose too, so the narrow
///     phase of the pair sees both bodies where \alg{A.2} puts them and finds the contact EveryPass
///     finds. Left where it stands, the partner would be off by up to exactReach ℓ, far more than
///     the margin (10⁻³ of the smallest ℓ): a thin plate, fast under gravity alone for its small ℓ,
///     moves down g Δt² in every pass under a resting box that stays, and their contact is never
///     seen. Widening the pair's margin by the partner's reach instead would find that contact too,
///     but also pairs that come apart in the pass, and would need each point's depth corrected by
///     the partner's displacement to tell them apart; moving the partner is the algorithm as
///     written and costs one pose update per pass. The partners go back to their current poses
///     before COLLIDE, with velocities recomputed exactly as they were, so the slow pairs'
///     prediction and the impulses see every slow body in one place.
///
///   - Pairs moving together (ImpulseParams::pairReach): a pair with a fast body whose two
///     bodies move together, Δt |v'_a - v'_b| plus both turns Δt |ω| ρ within exactReach ℓ of
///     the smaller, is cached and predicted as a slow pair is, if its narrow phase at the
///     current poses has points. The prediction is exact for any translation the two share,
///     so its error is bounded by their relative motion, not their speed: the cubes of a clump
///     flying on together after they meet are predicted, not looked at in every pass.
///     A pair that stops moving together in a pass (an impulse parted them) is gathered as
///     written in that pass.
///
///   Contacts of both kinds are ordered by pair, as EveryPass orders them. Speculative contacts
///   (Catto, "Speculative Contacts", GDC 2013) make the same first-order prediction. On a
///   resting stack every body is slow and a step costs one narrow phase instead of one per pass
///   (16 with the default iterations), which was most of its cost; in an impact the fast bodies
///   cost what they cost as written.
///
///   DEVIATION(A.2 RESOLVECOLLISIONS L2-L3, RESOLVECONTACTS L2-L3): slow bodies, and fast
///   pairs moving together, are not moved to their predicted poses. The cache is rebuilt when a body's mobility changes (a sleeping
///   body wakes, \thesis{§4.5}) and every step. A fast body's slow partner is moved only for
///   the narrow phase of its pairs with fast bodies. What differs from EveryPass: a slow pair's
///   depth by the rotation error above; the lever arm of an impulse in a slow pair by at most
///   its bodies' reach (exactReach ℓ, 1 % of a box's size by default); and a slow pair's
///   manifold points, which stay those found at the current pose.
///
/// Where COLLIDE acts, in both modes. \alg{A.2} collides the pairs while the bodies stand at
/// their predicted poses and reverts them after (RESOLVECOLLISIONS L4-L6). Here begin() puts
/// every body back before it returns; each contact keeps the lever arms r' = p - x' of the
/// poses it was found at (ImpulseContact::ra, rb), so the impulse's linear and angular parts,
/// j n and r' × j n, are those of \alg{A.2}. What changes is the inverse inertia the impulse is
/// computed with: the current pose's I⁻¹(q), giving ω = I⁻¹(q) L, where \alg{A.2} has the
/// predicted pose's I⁻¹(q') and ω' = I⁻¹(q') L.
///
///   DEVIATION(A.2 RESOLVECOLLISIONS L4-L6, RESOLVECONTACTS L4-L6): revertToOriginalPositions
///   before COLLIDE instead of after. The state holds the current orientation q, and its kinetic
///   energy is ½ P·v + ½ L·I⁻¹(q) L. An impulse computed with I⁻¹(q') removes energy measured
///   with I⁻¹(q'), not with I⁻¹(q): the angular momentum it leaves can hold more energy at q
///   than the step began with. On a fast-spinning flat body the difference is large: in random
///   scene 22811 (verification/stress_test.cpp) a 284 kg plate 0.27 m thick, at 20 rad/s
///   (|ω| Δt = 0.33 rad), hits the ground with e = 0.9; the impulse took 15.2 kJ from the plate
///   measured at q' and added 26.0 kJ measured at q, the next pass added 9.2 kJ more, and the
///   plate left the ground at 36.5 m/s after hitting it at 30.5 m/s. With velocity and impulse
///   measured with the same lever arm and the state's inertia, the impulse changes the energy
///   by ½ j (1 - e) v⁻ <= 0 (newtonian_impulse.hpp). The velocity it stops is also the one the
///   step moves with: the position update turns the body by Δt ω with ω = I⁻¹(q) L held, which
///   carries the material point at x + r to x' + r' arriving with velocity v + ω × r', the
///   approach COLLIDE now sees (ω' × r' is not what the step integrates).
#pragma once

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "boxsim/collision/contact.hpp"
#include "boxsim/collision/obb.hpp"
#include "boxsim/collision/separating_axis.hpp"
#include "boxsim/core/world.hpp"
#include "boxsim/impulse_damped/contact_islands.hpp"
#include "boxsim/impulse_damped/contact_normal.hpp"
#include "boxsim/impulse_damped/impulse_params.hpp"

namespace boxsim {

/// Whether a velocity includes the gravity of the coming step (\alg{A.2} COLLIDE's argument).
enum class GravityMode {
  VelocityNoGravity,    ///< v as it is
  VelocityPlusGravity,  ///< v + g Δt: what the body will have once gravity is integrated
};

/// The velocity a GravityMode adds over a step of dt s: g Δt (m/s) or zero.
inline Vec3 gravityVelocity(const World& world, GravityMode gravity, double dt) {
  return gravity == GravityMode::VelocityPlusGravity ? Vec3(dt * world.gravity) : Vec3(Vec3::Zero());
}

/// The pose of one body with the derived values that depend on it only, so putting it back
/// needs no recomputation of R and Iinv.
struct SavedPose {
  Vec3 x;     ///< m
  Quat q;     ///< orientation
  Mat3 R;     ///< rotation matrix of q
  Mat3 Iinv;  ///< world inverse inertia at q
  /// Whether the body was immovable when saved: a sleeping body woken in between (§4.5) has
  /// other mass properties now, so its derived values must be recomputed, not restored.
  bool immovable;
};

/// Poses of every body, in body order, for putting them back (\alg{A.2}
/// revertToOriginalPositions).
using SavedPoses = std::vector<SavedPose>;

/// integrateObjectPositions of \alg{A.2} for one movable body: x += Δt (v + extra), q turned by
/// Δt ω (one explicit quaternion step, renormalised; with Integrator::SplitRotation, by
/// splitRotation instead); R, I⁻¹, v and ω follow. Only those two integrators are accepted.
void movePredicted(RigidBody& body, double dt, const Vec3& extraVelocity,
                   Integrator integrator = Integrator::SemiImplicitEuler);

/// integrateObjectPositions of \alg{A.2}: moves every movable body to x + Δt (v + extra) and
/// turns it as movePredicted does with `integrator`; returns the poses before.
SavedPoses predictPositions(World& world, double dt, const Vec3& extraVelocity,
                            Integrator integrator = Integrator::SemiImplicitEuler);

/// Puts one body back to a saved pose, reusing the saved R and Iinv unless the body's
/// mobility changed since (then everything derived is recomputed); v and ω are recomputed.
void restorePose(RigidBody& body, const SavedPose& pose);

/// Puts back poses saved by predictPositions; momenta are left as they are. Immovable bodies,
/// which predictPositions does not move, are skipped.
void revertPositions(World& world, const SavedPoses& saved);

/// gatherCollisions at predicted positions, pass after pass, in either mode of the file
/// comment. It owns the contact-normal model (\thesis{§3.3.2}), whose memory of closest faces
/// runs from step to step. Use: for every pass, begin() then end(); once per step, endStep().
class ContactGathering {
 public:
  /// Gathering with the given parameters (mode, normal model, widening).
  explicit ContactGathering(const ImpulseParams& params = {});

  /// \alg{A.2} L2-L3 of a pass: the contacts at the positions predicted with v' = v (+ g Δt
  /// for movable bodies under VelocityPlusGravity), every pair closer than `margin` m, one
  /// ImpulseContact per pair in a fixed order, with the lever arms of its material points where
  /// the bodies stand: every body is back at its pose before the call when this returns (the
  /// file comment, "Where COLLIDE acts"; with ImpulseParams::commonLeverPoint, from the current
  /// centres to one point, the midpoint of the two). The result stays valid until the next call.
  std::vector<ImpulseContact>& begin(World& world, double dt, GravityMode predict,
                                     double margin);
  /// OncePerStep: the step's narrow phase at the current poses and its candidate pairs (the
  /// file comment), which the first begin() of the step would otherwise find, with the same
  /// arguments; nothing under EveryPass. Lets a caller time it apart from the passes.
  void beginStep(const World& world, double dt, GravityMode predict, double margin);
  /// Ends a pass. \alg{A.2} L6, revertToOriginalPositions, already happened in begin().
  void end(World& world);
  /// Ends the step: the closest faces seen become the previous step's, and the cached contacts
  /// are dropped (the step moves the bodies).
  void endStep();

  /// candidatePairs(world, margin) for the bodies where they stand after the step's passes
  /// (FIXCONTACTCONSTRAINTS, \alg{A.2} L5), taken from the step's candidates instead of a
  /// broad phase: a pair of bodies whose bounds lie inside their bounds of the step's sweep
  /// (setGuard) is a candidate if it passes the test at all (the sweep ran with a margin of
  /// at least `margin`), and the few bodies outside theirs are tested against every body.
  /// Returns false, leaving `pairs` as it was, when the step's candidates cannot tell:
  /// EveryPass, no passes since endStep, bodies whose mobility changed since the sweep, a
  /// margin wider than the sweep's, or many bodies outside their bounds.
  bool stepPairs(const World& world, double margin, std::vector<std::pair<int, int>>& pairs) const;

  /// OncePerStep: the islands of the step's candidate pairs (contact_islands.hpp), kept up to
  /// date pass by pass; a pass skips the bodies of settled islands (they stand, move and touch
  /// as in the pass that settled them). Null under EveryPass, which has no candidates.
  ContactIslands* islands() {
    return params_.gathering == ContactGatheringMode::OncePerStep ? &islands_ : nullptr;
  }

  /// The normal model and its memory, for contacts gathered outside the passes.
  ContactNormalTracker& normals() { return normals_; }
  /// Narrow phases run since construction (OncePerStep: cache builds), for tests and benches.
  long narrowPhases() const { return narrowPhases_; }
  /// OncePerStep: narrow phases of pairs with a fast body at the poses of a pass, since
  /// construction, for tests and benches.
  long passNarrowPhases() const { return passNarrowPhases_; }
  /// OncePerStep: bodies that sat a pass out because their island was settled (islands()),
  /// summed over the passes since construction, for tests and benches.
  long skippedBodyPasses() const { return skippedBodyPasses_; }

 private:
  /// One manifold point with the parts of its predicted depth that do not change in a step.
  struct CachedPoint {
    Vec3 position;     ///< m, world, at the current pose
    double depth;      ///< m, along the manifold normal at the current pose
    Vec3 ra;           ///< p - x_a, m
    Vec3 rb;           ///< p - x_b, m
    Vec3 raCrossN;     ///< r_a × n, m
    Vec3 rbCrossN;     ///< r_b × n, m
    double nDotRa;     ///< n · r_a, m
    double nDotRb;     ///< n · r_b, m
  };
  /// One cached pair: the contact as COLLIDE will see it and its manifold's points.
  struct CachedPair {
    ImpulseContact contact;        ///< bodies and the model's normal
    /// The manifold at the current pose (its normal, a to b, is the direction the depths are
    /// measured in; its kind and normal name the face the normal model remembers).
    ContactManifold manifold;
    std::array<CachedPoint, 4> points;
    int count;
    bool remembered;  ///< its face was handed to the normal model since it last was fast
    /// A pair with no point to predict from (count 0) gets the narrow phase where its slow
    /// bodies stand, the same in every pass of the step: its manifold, found in the first pass
    /// that needs it (index into exactManifolds_), or kExactUnknown.
    int exact = kExactUnknown;
  };
  static constexpr int kExactUnknown = -1;
  /// What a pass reads of a cached pair before its points, kept apart from them (a CachedPair
  /// is about a kilobyte, and most pairs of a pile stop here): its bodies and how near its
  /// points can come.
  struct PairReach {
    int a, b;              ///< body indices, a < b
    int count;             ///< its points
    double deepest = 0.0;  ///< m, the largest depth of its points
    double leverA = 0.0;   ///< m, the largest |r_a| of its points
    double leverB = 0.0;   ///< m, the largest |r_b| of its points
  };

  /// begin() without ImpulseParams::commonLeverPoint: the contacts with the lever arms of the
  /// poses they were found at.
  std::vector<ImpulseContact>& gather(World& world, double dt, GravityMode predict, double margin);
  /// m: how far a body moves in a pass with its current velocities, Δt (|v'| + |ω| ρ).
  double reach(const RigidBody& body, const Vec3& gravityStep, double dt) const;
  /// Whether the cache was built for bodies of the same mobility as the world's now.
  bool cacheCovers(const World& world) const;
  void buildCache(const World& world, const Vec3& gravityStep, double dt, double margin);
  /// Records body i's velocity of the pass, v' (v + g Δt when movable), and its turn Δt |ω| ρ
  /// (m), for movingTogether.
  void setPassMotion(const RigidBody& body, int i, const Vec3& gravityStep, double dt);
  /// Whether bodies a and b move together in this pass: Δt |v'_a - v'_b| plus both turns
  /// within exactReach ℓ of the smaller body (ImpulseParams::pairReach).
  bool movingTogether(int a, int b) const;
  /// Whether a cached pair with a fast body is predicted from the cache in this pass, not
  /// gathered as written: it has points, pairReach is on and its two bodies move together.
  bool predictedTogether(const PairReach& reach) const;
  /// Whether a point of the cached pair `reach` may come within `margin` (m) in this pass:
  /// false only when predictedContact would find none.
  bool mayTouch(const PairReach& reach, double margin) const;
  /// The Taylor-predicted contact of a cached pair of slow bodies; false when no point is
  /// within the margin.
  bool predictedContact(const World& world, const CachedPair& pair, const Vec3& gravityStep,
                        double dt, double margin, ImpulseContact& contact) const;
  /// The contact of bodies i < j from their manifold m (the normal model's choice); false
  /// when m has no point.
  bool contactOf(const World& world, int i, int j, ContactManifold m, ImpulseContact& contact);
  /// The narrow phase of a pair of the step's candidates where its bodies stand, trying its
  /// last separating axis first and remembering the axis of this test; false (manifold left
  /// as it was) when they do not touch within the margin.
  bool candidateManifold(const World& world, std::size_t candidate, double margin,
                         ContactManifold& manifold);
  /// Brings the islands up to the step's candidates and cached pairs: built anew after a sweep,
  /// joined with the pairs added since otherwise.
  void refreshIslands(const World& world);
  /// The step's candidate pairs: one sweep over every body's bounds from setGuard, with
  /// sweepMargin_; bodies must stand at their current poses.
  void sweepCandidates(const World& world, const Vec3& gravityStep, double dt);
  /// Sets body i's bounds for the step's sweep from its current pose and velocities: its
  /// bounds stretched along kGuardFactor times its displacement in a pass and grown sideways,
  /// holding its bounds grown by the slow widening.
  void setGuard(const World& world, int i, const Vec3& gravityStep, double dt);
  /// m: the rounding allowance of a bounds test on a body at x with half diagonal ρ (m):
  /// bounds computed at two poses differ from the exact motion by rounding of order |x| + ρ.
  static double roundingSlack(const RigidBody& body, double halfDiagonal);
  /// Whether body i, moved by `displacement` (m) and turned so that no corner moves more than
  /// `turn` (m), stays inside its bounds for the sweep.
  bool withinGuard(const RigidBody& body, int i, const Vec3& displacement, double turn) const;
  /// Gives the `outgrown` bodies bounds for their current velocities and adds the
  /// candidates that brings (bodies at their current poses).
  void growCandidates(const World& world, const Vec3& gravityStep, double dt,
                      const std::vector<int>& outgrown);
  /// Sorts the bodies' bounds for the step's sweep (guardLo_, guardHi_) into guardIndex_.
  void indexGuards(const World& world);
  /// Calls visit(j) for every body j whose bounds for the sweep may lie within `margin` (m) of
  /// [lo, hi] (m) along every axis, from guardIndex_: a superset of the bodies boundsWithin
  /// passes, some perhaps twice, never one it fails along x.
  template <class Visit>
  void forGuardsNear(const Vec3& lo, const Vec3& hi, double margin, const Visit& visit) const;

  /// A pair that may come within the margin during the step, with the axis that last
  /// separated it (separatedBeyond), if any, and the answer of its last pass.
  struct Candidate {
    int a;                      ///< body index, a < b
    int b;                      ///< body index
    SeparatingAxisResult axis;  ///< kind and indices of the last test's axis
    bool apart;                 ///< the last test found no contact within the margin
    /// The poses (poseStamp_) a and b stood at in the pass that last looked at the pair; 0:
    /// never looked at. When both are the same in a later pass, so is the answer.
    std::uint64_t stampA = 0, stampB = 0;
    /// The manifold found then (index into manifolds_), or -1: no contact within the margin.
    int manifold = -1;
    /// The pair's entry in the cache (index into pairs_), or -1: not cached.
    int cached = -1;
  };

  /// The bodies' bounds for the step's sweep sorted along x, so growCandidates finds a
  /// body's neighbours by one binary search and a scan of a slab instead of testing every
  /// body. Sorted when first needed after a sweep; bounds set again since (setGuard) are listed
  /// in `regrown` and tested directly, as are the bodies in `direct`.
  struct GuardIndex {
    bool valid = false;
    std::uint64_t stamp = 0;   ///< stampCounter_ when sorted: guardStamp_ above it is newer
    std::vector<int> order;    ///< bodies by guardLo_.x
    std::vector<double> lo;    ///< m, guardLo_.x in that order
    std::vector<double> maxHi; ///< m, the largest guardHi_.x up to each place in that order
    std::vector<int> direct;   ///< wide immovable bodies and bounds that are not finite
    std::vector<int> regrown;  ///< bodies whose bounds were set again since the sort
  };

  /// A fast body's predicted pose in a pass (A.2 L2) with what it was computed from. Between
  /// two passes of a step a body's current pose does not change, so while its momenta and
  /// velocities stay bitwise the same (no impulse of the passes reached it) its predicted pose
  /// does too and is copied instead of recomputed.
  struct PredictedPose {
    Vec3 P, L, v, omega;  ///< the key: momenta and velocities at the current pose
    Vec3 x;               ///< m, predicted
    Quat q;               ///< predicted
    Mat3 R, Iinv;         ///< derived at the predicted pose
    Vec3 vPredicted, omegaPredicted;  ///< velocities movePredicted leaves (ω = I⁻¹' L)
    Vec3 lo, hi;          ///< bounds at the predicted pose (obbBounds, margin 0), m
    /// Identifies this pose (the poseStamp_ of a body standing at it); valid in this cache
    /// only when greater than buildStamp_.
    std::uint64_t stamp = 0;
  };
  /// What a pass works out from a body's velocities before moving it: its reach and whether
  /// its predicted bounds stay inside its guard, kept while v and ω stay bitwise the same.
  struct PassMotion {
    Vec3 v, omega;            ///< the key
    double reach = 0.0;       ///< m, Δt (|v'| + |ω| ρ)
    double turn = 0.0;        ///< m, Δt |ω| ρ
    bool withinGuard = false; ///< withinGuard's answer for the guard of guardStamp
    std::uint64_t guardStamp = 0;  ///< the guard withinGuard was asked about; 0: not asked
    std::uint64_t stamp = 0;  ///< valid when greater than buildStamp_
  };

  /// Makes predicted_[i] hold what movePredicted would make of body i now (kept from an
  /// earlier pass when its key is unchanged); the body stays where it is.
  void preparePredicted(const RigidBody& body, int i, double dt, const Vec3& gravityStep);
  /// Moves body i to its predicted pose of this pass (predicted_[i]), remembering where it
  /// stood, if it stands at that pose for this pass (moved_ or partner_) and is not there yet.
  void place(World& world, int i);
  /// Body i's box where it stands in this pass: at its predicted pose (moved_ or partner_),
  /// placed or not, else where it is.
  Obb passBox(const World& world, int i) const;

  ImpulseParams params_;
  ContactNormalTracker normals_;
  std::vector<ImpulseContact> contacts_;
  SavedPoses saved_;             ///< poses before the pass, of the bodies placed_
  std::vector<char> moved_;      ///< per body: a fast body standing at its predicted pose
  std::vector<char> placed_;     ///< per body: actually moved there (place), saved_ holds its pose
  bool cached_ = false;
  std::vector<CachedPair> pairs_;
  /// Per entry of pairs_, in its order (increasing (a, b)): PairReach.
  std::vector<PairReach> pairReach_;
  std::vector<Vec3> passU_;       ///< m/s, per body: v' of this pass (setPassMotion)
  std::vector<double> passTurn_;  ///< m, per body: Δt |ω| ρ of this pass
  std::vector<double> passSpin_;  ///< rad/s, per body: |ω| of this pass
  double passDt_ = 0.0;           ///< s, the Δt of passU_ and passTurn_
  std::vector<char> immovable_;   ///< each body's mobility when the cache was built
  std::vector<char> fast_;        ///< per body: fast when the cache was built, so not in it
  double cacheMargin_ = 0.0;
  /// m: the margin of the step's sweep, the passes' margin widened by g Δt², the width
  /// restingContactMargin adds, so stepPairs covers FIXCONTACTCONSTRAINTS' contacts too.
  double sweepMargin_ = 0.0;
  long narrowPhases_ = 0;
  long passNarrowPhases_ = 0;
  long skippedBodyPasses_ = 0;
  /// The sweep's pairs in increasing (a, b) order, then those growCandidates added since, in
  /// the order it added them.
  std::vector<Candidate> candidates_;
  std::vector<std::pair<int, int>> sweptKeys_;  ///< the sweep's pairs: candidates_ up to its size
  std::vector<std::pair<int, int>> grownKeys_;  ///< the pairs added since, sorted (empty: none)
  std::vector<double> halfDiagonal_;   ///< m, per body: |h|, the ρ of reach()
  std::vector<double> slowReach_;      ///< m, per body: exactReach ℓ, the slow bodies' bar
  std::vector<Vec3> lo_, hi_;          ///< bounds at the current poses (obbBounds, margin 0)
  std::vector<Vec3> guardLo_, guardHi_;  ///< bounds in the step's sweep (setGuard)
  std::vector<int> outgrown_;          ///< this pass: fast bodies that outgrew their bounds
  std::vector<char> isOutgrown_;       ///< per body, in growCandidates: in outgrown_
  GuardIndex guardIndex_;              ///< guardLo_, guardHi_ sorted (growCandidates)
  std::vector<int> fastBodies_;        ///< this pass: bodies fast now or at the cache's build
  std::vector<char> hasCandidate_;     ///< per body: in at least one candidate pair
  std::vector<double> passReach_;      ///< m, per movable body: its reach in this pass
  std::vector<char> partner_;          ///< per body: a slow partner standing at its predicted pose for the narrow phase
  std::vector<int> partners_;          ///< this pass: the slow partners moved
  std::vector<ImpulseContact> fastContacts_;  ///< this pass: the pairs with a fast body, by pair
  std::vector<PredictedPose> predicted_;  ///< per body: its last predicted pose in the step
  std::vector<PassMotion> motion_;        ///< per body: its reach and guard test of the last pass
  std::vector<std::uint64_t> guardStamp_;  ///< per body: a new stamp each time setGuard runs
  std::uint64_t stampCounter_ = 0;        ///< the last stamp handed out
  double guardScale_ = 1.0;  ///< this step's stretch of the swept bounds, times kGuardFactor
  /// Per body, this pass: which pose it stands at, its predicted pose's stamp or, at its
  /// current pose, buildStamp_.
  std::vector<std::uint64_t> poseStamp_;
  /// The stamp of the current poses since the last build of the cache; predicted poses with
  /// smaller stamps are from before it and invalid.
  std::uint64_t buildStamp_ = 0;
  Vec3 predictedGravity_ = Vec3::Zero();  ///< the g Δt and Δt the predicted poses are for
  double predictedDt_ = 0.0;
  std::vector<ContactManifold> manifolds_;  ///< the candidates' last manifolds (Candidate)
  std::vector<ContactManifold> exactManifolds_;  ///< the cached pairs' narrow phases (CachedPair::exact)
  ContactIslands islands_;              ///< the islands of the candidates (islands())
  std::uint64_t sweeps_ = 0;            ///< sweeps of the candidates so far
  std::uint64_t islandSweep_ = 0;       ///< the sweep islands_ was built after
  std::size_t joinedCandidates_ = 0;    ///< candidates_ joined into islands_ so far
  std::vector<char> skip_;              ///< per body, this pass: its island is settled
};

}  // namespace boxsim
