/// \file
/// Damped integration, the thesis' real-time technique (\thesis{§5.2}, \alg{A.2}
/// DAMPEDINTEGRATION): Guendelman et al.'s collision and contact passes with the gravity trick,
/// then gravity, damping, fixing contact constraints and classifying geometric stability.
/// Around it, two of the basic techniques of \thesis{§4}: sleeping bodies at rest
/// (computational stability, \thesis{§4.5}) and random perturbation of high-speed collisions
/// (visual plausibility, \thesis{§4.2}). The method "damped".
#pragma once

#include <utility>
#include <vector>

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/core/gravity_frame.hpp"
#include "boxsim/core/stepper.hpp"
#include "boxsim/geometric_stability/geometric_stability.hpp"
#include "boxsim/impulse_damped/centre_over_support.hpp"
#include "boxsim/impulse_damped/contact_gathering.hpp"
#include "boxsim/impulse_damped/friction_totals.hpp"
#include "boxsim/impulse_damped/continuous_collision.hpp"
#include "boxsim/impulse_damped/dampen_objects.hpp"
#include "boxsim/impulse_damped/friction_slides.hpp"
#include "boxsim/impulse_damped/fix_contact_constraints.hpp"
#include "boxsim/impulse_damped/impulse_params.hpp"
#include "boxsim/impulse_damped/impulse_pass.hpp"
#include "boxsim/impulse_damped/shock_propagation.hpp"
#include "boxsim/impulse_damped/sleeping.hpp"
#include "boxsim/impulse_damped/visual_plausibility.hpp"

namespace boxsim {

/// Parameters of damped integration; each stage can be switched off for ablations.
struct DampedIntegrationParams {
  ImpulseParams impulse;          ///< collision and contact passes (\alg{DAMPEDINTEGRATION L1-L2})
  DampingParams damping;          ///< DAMPENOBJECTS (\alg{DAMPEDINTEGRATION L4})
  /// FIXCONTACTCONSTRAINTS (\alg{DAMPEDINTEGRATION L5}); its slop also wakes
  FixContactParams fixContacts;
  /// SETGEOMETRICALLYSTABLE (\alg{DAMPEDINTEGRATION L6})
  GeometricStabilityParams geometricStability;
  SleepParams sleep;              ///< sleeping bodies at rest (\thesis{§4.5}), on by default
  PlausibilityParams plausibility;  ///< perturbed fast collisions (\thesis{§4.2}), off by default
  /// Continuous collision detection for fast bodies, off by default: when on, a step in which a
  /// fast body would reach another is split at the first time of impact
  /// (continuous_collision.hpp), so the passes gather the contact before the body is past it.
  ContinuousCollisionParams continuousCollision;
  /// Run DAMPENOBJECTS' momentum damping (\alg{DAMPENOBJECTS L1-L21}).
  bool damp = true;
  /// Also damp bodies that only collided in the step (RESOLVECOLLISIONS), not just those in
  /// contact. Off: DAMPENOBJECTS L2 damps bodies that "had a contact interaction", and the thesis
  /// tells contact interactions from collision interactions (\thesis{§2}, \thesis{§5.3}: bodies in
  /// resting contact). On, a clump of 100 cubes thrown together (Fig. 6.7) comes to rest by about
  /// 17 s instead of scattering for ever.
  bool dampCollidingBodies = false;
  bool fixContactConstraints = true;   ///< run FIXCONTACTCONSTRAINTS
  bool useGeometricStability = true;   ///< run SETGEOMETRICALLYSTABLE and COLLIDE L11-L14
  /// Speed only, the same bits either way (tested): RESOLVECOLLISIONS (\alg{DAMPEDINTEGRATION L1})
  /// stops after a pass that changed no body's momenta or mobility, since every later pass would
  /// repeat it. Not written into output headers, as it changes no result.
  bool stopUnchangedCollisionPasses = true;
  /// Speed only, the same bits either way (tested): the collision and contact passes
  /// (\alg{DAMPEDINTEGRATION L1-L2}) skip, for the rest of their loop, the islands of the step's
  /// contact graph that a pass left unchanged (contact_islands.hpp says when that is exact). Needs
  /// ImpulseParams::gathering OncePerStep, which finds the islands; not written into output
  /// headers.
  bool islandSettling = true;
  /// In a world with friction, shock propagation after RESOLVECONTACTS (propagateShockDamped,
  /// DEVIATION(A.2)): the passes do not settle the leaning columns friction holds. A frictionless
  /// world's step is \alg{A.2} whatever this says.
  bool shockPropagation = true;
  /// In units of g Δt: the sweep leaves to the passes a pair approaching slower than
  /// shockSettledSpeed or faster than shockRestingSpeed (propagateShockDamped's settledSpeed and
  /// restingSpeed). Measured with μ = 0.5, the bounds 0.1 and 2 against none: Fig. 6.6's shot
  /// base-20 pyramid, mean penetration over 8 s 1.1 mm (2.7; 1.8 with no sweep); the shot
  /// base-10 pyramid, every box asleep again (20 awake for good); two boxes gripping on a 30°
  /// plank, 0.4 mm apart after 2 s as with no sweep (3.0). The columns the sweep is for approach
  /// at about 1 g Δt.
  double shockSettledSpeed = 0.1;
  double shockRestingSpeed = 2.0;  ///< see shockSettledSpeed
  /// >= 1: the sweep visits each level's contacts up to this many times, their normal impulses
  /// accumulated and kept non-negative, until a visit changes nothing (propagateShockDamped).
  /// 1: each contact's impulse once, in order, which left a body resting on several supports
  /// turning, tilted into them, and lifted out by FIXCONTACTCONSTRAINTS (a tower of twelve
  /// layers of crossed planks built touching with μ = 0.5 gained 7.7 J in its first 0.13 s);
  /// 8: that tower and one of eight layers stand with their energy unchanged, and the same tower
  /// dropped layer by layer from 1 cm apart loses 19 J instead of gaining up to 34 J on the way
  /// (impulse chapter, "Coulomb friction"). In the 343-cube pile with μ = 0.5 the boxes at rest
  /// that report a fall are as few as with one visit (friction_test's count over six starts:
  /// 45 against 43; 194 with no sweep).
  int shockIterations = 8;
  /// DEVIATION(RESOLVECOLLISIONS L1), off by default (0: \alg{A.2} as written): at most this
  /// many collision passes after the ImpulseParams::collisionIterations, each run only while the
  /// pass before it still stopped an impact (impactReach). A pass gathers its contacts before it
  /// collides them, and equal masses share each inelastic impulse, so a landing's stop travels
  /// through a column of boxes that fall together a box at a time, back and forth: with five
  /// passes the upper boxes of ten cubes landing at 17 m/s 2 cm apart are still falling when
  /// RESOLVECOLLISIONS ends, and sink 206 mm into those below (with 20 impact passes, 1.2 mm;
  /// test "With impact passes a column ..."). Measured with the benchmark's yardstick
  /// (boxsim_peers, engine damped+impact, 20 passes; 4 nudged starts, 2 at e = 0.5), mean /
  /// final / largest penetration: the 1000-cube clump at e = 0 with μ = 0.5, which lands at
  /// 17 m/s, 27.0 / 129 / 236 mm -> 8.4 / 3.0 / 133 mm; frictionless, 19.5 / 8.7 / 70 mm ->
  /// 12.6 / 7.6 / 45 mm; at e = 0.5 12.0 / 85 / 141 mm -> 4.7 / 34 / 60 mm; the 343-cube pile
  /// at e = 0, 3.6 / 0.7 / 56 mm -> 3.5 / 1.6 / 39 mm. What they cost: docs/benchmarks.md, the
  /// rows "boxsim damped impact" and "boxsim damped μ impact".
  /// A step whose last collision pass stops no impact runs none (the same bits: test "Impact
  /// passes change nothing ..."), and such passes settle as the others do (islands, a pass that
  /// changed nothing).
  int impactPasses = 0;
  /// In units of ℓ (the smaller box's smallest half extent) per Δt, > 0: an impact (for
  /// impactPasses) is a COLLIDE of a collision pass that gives an impulse to a pair approaching
  /// faster than this, approachSpeed Δt > impactReach ℓ. 0.05: 2.5 cm a step for unit cubes,
  /// 1.5 m/s at 60 Hz, nine times the g Δt a resting box approaches with; what the passes leave
  /// closes at most this much in the step.
  double impactReach = 0.05;
};

/// Where the time of damped integration's steps goes, by stage of \alg{A.2} DAMPEDINTEGRATION:
/// wall-clock seconds summed over the steps taken while a stepper held the profile
/// (DampedIntegrationStepper::setProfile), for benches. Each stage's time includes the contact
/// gathering and narrow phases it runs.
struct DampedStepProfile {
  /// s, the narrow phase of the slow pairs at the step's start and the step's candidate pairs
  /// (ContactGathering::beginStep), before \alg{DAMPEDINTEGRATION L1}
  double stepContacts = 0.0;
  double collisionPasses = 0.0;       ///< s, RESOLVECOLLISIONS (\alg{DAMPEDINTEGRATION L1})
  double contactPasses = 0.0;         ///< s, RESOLVECONTACTS (\alg{DAMPEDINTEGRATION L2})
  /// s, with friction, the shock propagation sweep after RESOLVECONTACTS (propagateShockDamped)
  double shockSweep = 0.0;
  /// s, \alg{DAMPEDINTEGRATION L3-L4} (DAMPENOBJECTS' position update included)
  double velocitiesAndDamping = 0.0;
  /// s, FIXCONTACTCONSTRAINTS (\alg{DAMPEDINTEGRATION L5}) with its contacts found again
  double fixContacts = 0.0;
  double stability = 0.0;             ///< s, SETGEOMETRICALLYSTABLE (\alg{DAMPEDINTEGRATION L6})
  /// s, \thesis{§4.5}: sleeping bodies put in place as immovable before the passes, and bodies put
  /// to sleep or kept awake after \alg{DAMPEDINTEGRATION L6} (with the normal model's end of step)
  double sleeping = 0.0;
  long steps = 0;  ///< steps profiled (pieces of a step split by continuous collision each count)
  /// The work of the profiled steps that had a body awake (the others do nothing):
  long workSteps = 0;       ///< such steps
  long narrowPhases = 0;    ///< separating-axis tests run in them (KeptNarrowPhase's and the passes')
  long passNarrowPhases = 0;  ///< of those, the passes' tests of pairs with a fast body
  /// Of those, the tests of the step's start (stepContacts: the slow pairs' narrow phase)
  long startNarrowPhases = 0;
  /// Of those, FIXCONTACTCONSTRAINTS' (fixContacts: its contacts, its tests before and after
  /// each nudge, and the contacts found again after it)
  long fixNarrowPhases = 0;
  /// One-axis checks that answered for a test (separatedBeyond), apart from the tests counted
  /// above: a pair apart along the axis of its last test, in the passes (OncePerStepGathering)
  /// and in the kept narrow phases (KeptNarrowPhase::axisChecks).
  long axisChecks = 0;
  long keptNarrowPhases = 0;  ///< narrow phases handed back by KeptNarrowPhase instead of run
  long touchingPairs = 0;   ///< pairs in contact at their ends, summed (StepStats::contacts)
  long passes = 0;          ///< collision and contact passes run in them
  /// Whether to measure parallelWork (set before setProfile): the work the passes' threads
  /// share, for the model of more cores. Off by default: measuring plans every pass' pairs
  /// before their narrow phases, which costs a little on one thread.
  bool measureParallelWork = false;
  ParallelWork parallelWork;  ///< the shared work, when measureParallelWork
  /// s, the sum of the stages.
  double total() const {
    return stepContacts + collisionPasses + contactPasses + shockSweep + velocitiesAndDamping +
           fixContacts + stability + sleeping;
  }
};

/// DAMPEDINTEGRATION(Δt) of \alg{A.2} as a Stepper ("damped"), with sleeping and visual
/// plausibility.
///
/// **Sleeping** (\thesis{§4.5}): bodies at rest sleep, standing in as immovable, and wake when
/// disturbed, by the rule Sleeping states; the stepper calls it before the passes, before each
/// COLLIDE and after SETGEOMETRICALLYSTABLE.
///
/// **Visual plausibility** (\thesis{§4.2}): in RESOLVECOLLISIONS (\alg{DAMPEDINTEGRATION L1}) only,
/// a collision whose bodies approach faster than `plausibility.speedThreshold` has its normal
/// turned by a random rotation of at most `plausibility.maxAngleDeg` (VisualPlausibility).
class DampedIntegrationStepper final : public Stepper {
 public:
  /// A stepper with the given parameters; throws std::invalid_argument on iteration counts
  /// < 1, a time to sleep that is not a finite number > 0 s, negative or non-finite wake
  /// thresholds, a supportNormalY outside (0, 1), or invalid plausibility parameters.
  explicit DampedIntegrationStepper(const DampedIntegrationParams& params = {});
  std::string name() const override { return "damped"; }
  /// Coulomb friction at every contact (applyPatchFriction).
  bool modelsFriction() const override { return true; }
  /// Every parameter, including "seed", the plausibility generator's seed.
  std::map<std::string, std::string> parameters() const override;
  /// \alg{DAMPEDINTEGRATION L1-L6} for one step of dt s, with sleeping bodies standing in
  /// as immovable and high-speed collisions perturbed as the class comment describes; with
  /// continuous collision detection on, as several such steps that together cover dt, each
  /// ending at the next time of impact of a fast body (at least dt / maxSubsteps long).
  /// StepStats::sleeping counts the bodies asleep after the step.
  /// A.2 takes +y as up. A world whose gravity has an x or z part, or points up, is stepped
  /// turned so that its gravity points along -y and handed back turned back (GravityFrame,
  /// core/gravity_frame.hpp): the same motion, up to rounding, as the same scene built y-up.
  /// The flags below (geometricallyStable, asleep) are per body in either case.
  StepStats step(World& world, double dt) override;
  /// The geometric stability of each body found at the end of the last step
  /// (\alg{DAMPEDINTEGRATION L6}); a sleeping body keeps the flag it had when it fell asleep.
  const std::vector<char>& geometricallyStable() const { return stable_; }
  /// One flag per body of the world last stepped, 1 for a body asleep after the last step
  /// (\thesis{§4.5}). Bodies added to the world later start awake.
  const std::vector<char>& asleep() const { return sleeping_.asleep(); }
  /// The generator and counter of visual plausibility (\thesis{§4.2}).
  const VisualPlausibility& plausibility() const { return plausibility_; }
  /// Narrow phases the contact gathering has run (ContactGathering::narrowPhases).
  long narrowPhases() const { return gathering_.narrowPhases(); }
  /// The contact gathering, for its counters (ContactGathering::passNarrowPhases,
  /// ContactGathering::skippedBodyPasses).
  const ContactGathering& gathering() const { return gathering_; }
  /// Adds the time of every later step to `profile`, stage by stage (nullptr: stop). The
  /// profile must outlive its use; copies of the stepper share it.
  void setProfile(DampedStepProfile* profile) {
    profile_ = profile;
    gathering_.setParallelWork(profile && profile->measureParallelWork ? &profile->parallelWork
                                                                       : nullptr);
  }

 private:
  /// step() for a world whose gravity points down (gravityPointsDown) or is zero.
  StepStats stepUpright(World& world, double dt);
  /// \alg{DAMPEDINTEGRATION L1-L6} for dt s, as stepUpright() without continuous collisions.
  StepStats advance(World& world, double dt);
  /// \alg{RESOLVECOLLISIONS} (DAMPEDINTEGRATION L1): the collision passes, with high-speed
  /// collisions perturbed (§4.2) and, with impactPasses, more while a pass still stops an
  /// impact; marks in `touched` (one flag per body) the bodies that take part when
  /// dampCollidingBodies is on, and counts impulses and passes in `stats`; friction keeps its
  /// sums in `totals` (nullptr in a frictionless world).
  void resolveCollisions(World& world, double dt, double margin, std::vector<char>& touched,
                         FrictionTotals* totals, StepStats& stats);
  /// \alg{RESOLVECONTACTS} (DAMPEDINTEGRATION L2): the contact passes; marks in `touched` the
  /// bodies that take part, and counts impulses and passes in `stats`; friction's sums in
  /// `totals` as above.
  void resolveContacts(World& world, double dt, double margin, std::vector<char>& touched,
                       FrictionTotals* totals, StepStats& stats);
  /// \alg{FIXCONTACTCONSTRAINTS} (DAMPEDINTEGRATION L5), when on, and the contacts after it
  /// within the resting-contact margin, for SETGEOMETRICALLYSTABLE and sleeping, into
  /// lastContacts_.
  void fixContacts(World& world, double dt, double margin);
  /// The end of a step: the normal model's memory and the gathering's step end, sleeping
  /// (\thesis{§4.5}) decides from `contacts`, and `stats` gets the contact and sleeper counts.
  void endStep(World& world, double dt, const std::vector<ContactManifold>& contacts,
               StepStats& stats);

  DampedIntegrationParams params_;
  FrictionTotals frictionTotals_;  ///< the step's impulses per contact point, for friction
  ContactGathering gathering_;
  VisualPlausibility plausibility_;
  std::vector<char> stable_;
  /// SETGEOMETRICALLYSTABLE, its working lists kept from step to step.
  GeometricStability stability_;
  // The contacts at the end of the last step (FIXCONTACTCONSTRAINTS'), whose poses the next step
  // starts from: the support test of DAMPENOBJECTS reads them (DampingParams::supportTest); and
  // those poses (x, q per body), so that a world moved or changed between steps has its
  // contacts found again.
  std::vector<ContactManifold> lastContacts_;
  /// Per body: it touches another in lastContacts_ (with a predicted anchor only).
  std::vector<char> touchingAtStart_;
  std::vector<std::pair<Vec3, Quat>> lastPoses_;
  ContactIslands supportedIslands_;  ///< keepSupported's working room
  /// The working lists of a step, kept from step to step for their room: the bodies a step's
  /// passes touched (DAMPENOBJECTS' colliding bodies), and fixContacts'.
  std::vector<char> touched_;
  SavedPoses dampedPoses_;  ///< DAMPENOBJECTS' poses before L22
  /// The support verdicts with Coulomb's SupportVerdict::slides marked (worlds with friction).
  std::vector<SupportVerdict> slideVerdicts_;
  FrictionSlideLists slideLists_;  ///< markFrictionSlides' sums
  ShockLevels shockLevels_;        ///< propagateShockDamped's lists (worlds with friction)
  struct FixLists {
    std::vector<std::pair<int, int>> pairs;  ///< the broad phase's pairs
    std::vector<Vec3> before;                ///< per body, x before the nudges, m
    std::vector<char> nudged;                ///< per body, moved by a nudge
    FixContactOrder order;                   ///< L1's order
    BroadPhaseLists broadPhase;              ///< refindContacts' lists
    std::vector<ContactManifold> refound;    ///< the contacts after the nudges
  } fixLists_;  ///< fixContacts' lists
  /// The support test of DAMPENOBJECTS, its buffers kept from step to step.
  SupportTest supportTest_;
  Sleeping sleeping_;
  /// A world whose gravity does not point down, kept turned so that it does (step()).
  GravityFrame gravityFrame_;
  DampedStepProfile* profile_ = nullptr;  ///< where stage times go, or none
};

}  // namespace boxsim
