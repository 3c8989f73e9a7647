/// \file
/// Parameters of the impulse-based step (Guendelman, Bridson and Fedkiw, "Nonconvex Rigid
/// Bodies with Stacking", SIGGRAPH 2003, §7; \thesis{§2.5.2}, \thesis{§3.3.2}) and of the
/// thesis' damped integration (\thesis{§5.2}, \thesis{§5.3}, \alg{A.2}).
///
/// The thesis gives no values for the constants k1…k9 and ε1…ε11 of \alg{A.2}. Every one here
/// is chosen, justified, and expressed in units that scale with the body and the step, as
/// \thesis{§6.3.1} asks: velocities in units of g Δt (the speed gravity adds in one step, the
/// size of the velocity a resting box chatters with), angular velocities in units of g Δt / ℓ
/// (ℓ: the body's smallest half extent), lengths in units of ℓ, and damping factors as rates per
/// second turned into per-step factors exp(-λ Δt). A scene of 0.1 m boxes then behaves like a
/// scene of 1 m boxes seen through a lens.
#pragma once

#include <string>

#include "boxsim/core/enum_names.hpp"
#include "boxsim/core/integrator.hpp"
#include "boxsim/filtering/envelope.hpp"
#include "boxsim/impulse_damped/damping_params.hpp"

namespace boxsim {

/// How the normal of a contact between two interpenetrating boxes is chosen
/// (\thesis{§3.3.2}).
enum class ContactNormalModel {
  /// The axis of least penetration of the separating-axis test, recomputed every time.
  SeparatingAxis,
  /// The thesis' choice: the face found closest when the pair first touched is kept from the
  /// previous step, and its current normal is the contact normal (\thesis{§3.3.2}).
  PreviousClosestFace,
  /// The thesis' footnote: the gradient of an object-space signed distance of the box at the
  /// deepest penetrating corner, as Guendelman et al. do with signed distance grids.
  SignedDistance,
};

/// "separating_axis", "previous_closest_face" or "signed_distance".
std::string contactNormalModelName(ContactNormalModel model);

/// The names of the contact normal models.
inline constexpr EnumNames<ContactNormalModel, 3> kContactNormalModelNames{{
    {ContactNormalModel::SeparatingAxis, "separating_axis"},
    {ContactNormalModel::PreviousClosestFace, "previous_closest_face"},
    {ContactNormalModel::SignedDistance, "signed_distance"},
}};
/// Parses the names of contactNormalModelName(); throws std::invalid_argument on others.
ContactNormalModel parseContactNormalModel(const std::string& name);

/// How each pass finds the contacts at the predicted positions (contact_gathering.hpp).
enum class ContactGatheringMode {
  /// \alg{A.2} as written: every pass moves the bodies and runs the narrow phase there.
  EveryPass,
  /// One narrow phase per step, the passes' depths predicted to first order from it.
  OncePerStep,
};

/// "every_pass" or "once_per_step".
std::string contactGatheringName(ContactGatheringMode mode);

/// The names of the gathering modes.
inline constexpr EnumNames<ContactGatheringMode, 2> kContactGatheringNames{{
    {ContactGatheringMode::EveryPass, "every_pass"},
    {ContactGatheringMode::OncePerStep, "once_per_step"},
}};
/// Parses the names of contactGatheringName(); throws std::invalid_argument on others.
ContactGatheringMode parseContactGathering(const std::string& name);

/// The impulse-based step of Guendelman et al., shared by both techniques.
struct ImpulseParams {
  /// Passes of collision processing (restitution `restitution`), Guendelman §7: 5.
  int collisionIterations = 5;
  /// Passes of contact processing with the restitution ramp of \alg{RESOLVECONTACTS L5}: 10.
  int contactIterations = 10;
  /// How contact normals are chosen (collisions use the world's restitution, 0.9 by default
  /// as \thesis{§3.3.2}).
  ContactNormalModel normalModel = ContactNormalModel::PreviousClosestFace;
  /// m per m of box size: boxes closer than this count as touching when contacts are
  /// gathered (so a box resting exactly on another is "in contact"). 1e-3 ℓ.
  double contactMargin = 1e-3;
  /// How the passes gather contacts. OncePerStep, the default, runs one narrow phase per step
  /// instead of one per pass (contact_gathering.hpp states the deviation and its error bound).
  ContactGatheringMode gathering = ContactGatheringMode::OncePerStep;
  /// How the step's last stage moves the bodies with their new velocities (integrateObjectPositions,
  /// \alg{DAMPENOBJECTS L22}; Guendelman et al.'s position update). SemiImplicitEuler, the default
  /// and the thesis': x += Δt v and the explicit quaternion step q += ½ Δt ω q, renormalised.
  /// SplitRotation: the same x, and the rotation of integrator.hpp that keeps a free body's energy
  /// and |L| (a free box spinning near its intermediate axis gains 417 % of its energy in 10 s at
  /// 60 Hz under the default, measured). The velocities come from the impulses and gravity before
  /// the positions by construction, so ForwardEuler and RungeKutta4 are refused. The passes'
  /// predicted poses (\alg{RESOLVECOLLISIONS L2}) keep the explicit step.
  Integrator integrator = Integrator::SemiImplicitEuler;
  /// Where the impulses of a pass act. false, \alg{A.2} as written: on each body at the lever
  /// arm of the pose the contact was found at, r' = p - x' (contact_gathering.hpp, "Where
  /// COLLIDE acts"). The state stays at the current pose, so the two impulses ±J act at points
  /// x_a + r'_a and x_b + r'_b that lie Δt (v_b - v_a) apart, and the pair's angular momentum
  /// about a fixed point changes by Δt (v_a - v_b) × J: nothing when the bodies approach along
  /// the normal, 19 % of it in a glancing hit of two cubes at 60 Hz (measured;
  /// chapters/impulse_damped/README.md). true: both impulses act at the midpoint of those two
  /// points, q = ½ (x_a + r'_a + x_b + r'_b), with lever arms q - x from the current centres,
  /// which conserves the angular momentum up to rounding; the contacts, normals and the velocity
  /// stopped stay \alg{A.2}'s up to the O(Δt |v| |ω|) the moved lever arm changes. Both impulse
  /// and velocity use the same lever arm, so an impulse still never adds energy
  /// (newtonian_impulse.hpp). Off by default: the thesis' figures are made without it.
  bool commonLeverPoint = false;
  /// In units of ℓ, >= exactReach (OncePerStep): the margin of each movable body is widened by
  /// this when the step's contacts of slow bodies are cached, so that pairs a slow body can
  /// reach in the step are cached too. 0.05 ℓ: 2.5 cm for unit cubes, ten times the g Δt² a
  /// resting box moves in a 60 Hz step.
  double slowWidening = 0.05;
  /// In units of ℓ, >= 0 (OncePerStep): a body whose reach in a pass, Δt (|v'| + |ω| ρ), exceeds
  /// this is moved to its predicted pose and its pairs get the exact broad and narrow phase
  /// every pass; pairs of slower bodies use the Taylor prediction. 0.02 ℓ: 1 cm for unit cubes,
  /// a speed of 0.6 m/s at 60 Hz, above the 2 g Δt (0.33 m/s) a resting box chatters with,
  /// far below an impact.
  double exactReach = 0.02;
  /// OncePerStep: a pair with a fast body whose two bodies move together, Δt |v'_a - v'_b|
  /// plus both turns Δt |ω| ρ within exactReach ℓ (of the smaller body), is predicted like a
  /// pair of slow bodies (contact_gathering.hpp, "Pairs moving together"). false: every pair
  /// with a fast body gets the exact narrow phase in every pass.
  bool pairReach = true;
  /// OncePerStep: where the step's cache of slow pairs is found and its Taylor prediction
  /// starts. false (the default): at the current poses, each pass predicting the whole
  /// displacement Δt (v' + ω × r) to the pass' pose, and a body is fast when that exceeds
  /// exactReach ℓ. true: for a body fast at the step's start (and, under damped integration,
  /// touching another there: OncePerStepGathering::setTouching), at the pose the first pass
  /// predicts, x + Δt (v + g Δt) and q turned by Δt ω with the step's starting velocities, each
  /// pass predicting only how far its own prediction has moved from there, Δt (v' - v'_0) and
  /// Δt (ω - ω_0); such a body is fast when that exceeds exactReach ℓ. A falling or sliding body
  /// whose velocity the passes barely change is then slow, and its pairs cost a Taylor
  /// prediction instead of an exact narrow phase per pass.
  /// DEVIATION(RESOLVECOLLISIONS L2-L3, RESOLVECONTACTS L2-L3): as the slow pairs' prediction,
  /// from another starting pose.
  bool predictedAnchor = false;
  /// OncePerStep: a pair the step's cache would hold with an edge-edge manifold, or with none
  /// although within its margin, gets the narrow phase at every pass' predicted poses, as a
  /// pair with a fast body does, instead of the Taylor prediction of that manifold's points. The
  /// prediction follows the material points of the feature found at the start, and a small
  /// relative turn brings another corner of an edge-edge pair into contact: on the settling
  /// pile of 343 the cache missed contacts up to 7 mm deep that the exact narrow phase finds,
  /// all of them such pairs. Off by default while measured.
  bool exactEdgePairs = false;
  /// OncePerStep: a pair the step's cache holds with an edge-edge manifold keeps beside its
  /// point the corners of its best face within its margin, with their own normal, and each
  /// pass predicts the edge point or the corners (SlowPairCache::Alternate): the corners a
  /// small relative turn brings down are predicted as the point is, by Taylor expansion, with
  /// no narrow phase in the passes. On the settling pile of 343 a second after its drop the
  /// cache then misses none of the contacts deeper than 1 mm that the narrow phase at every
  /// pass' poses finds (contact_gathering_test). Off by default while measured: on, the pile of
  /// Fig. 6.7 comes to rest with no chatter left even without sleeping, and a brick wall's
  /// upper rows stop creeping without the rest of grounded bodies (friction_test's premises).
  /// DEVIATION(RESOLVECOLLISIONS L2-L3, RESOLVECONTACTS L2-L3): as the slow pairs' prediction.
  bool edgeCorners = false;
  /// Speed only, the same bits either way (tested): the narrow phases of the step go through a
  /// KeptNarrowPhase (collision/kept_narrow_phase.hpp), which hands a pair's separating-axis
  /// test back while both boxes stand exactly where they stood when it ran. Not written into
  /// output headers, as it changes no result.
  bool keepNarrowPhases = true;
  /// Threads of a step, >= 1: COLLIDE's loop (impulse_pass.hpp, "Threads"), whose contacts
  /// run in dependency levels of A.2's own order, the narrow phases of the pairs with a fast
  /// body (once_per_step_gathering.hpp), each pair's into its own slot, and the kept narrow
  /// phases of the step's start and of FIXCONTACTCONSTRAINTS (KeptNarrowPhase::collideAll). The
  /// same bits for any number (tested). 1, the default: no second thread. More are used only
  /// where OpenMP was found at build time (not in the WebAssembly build), and in a loop of
  /// `parallelContacts` contacts a level or `parallelNarrowPhases` narrow phases.
  int threads = 1;
  /// Contacts a dependency level of a pass needs on average before COLLIDE's loop is shared
  /// among `threads`, a frictional contact counting as 4 (its five friction rows): below it the
  /// threads' meeting at every level costs more than they save. 48, measured on this project's
  /// 2-core machine: the 1000-cube clump at e = 0 (about 14 frictionless contacts a level) ran
  /// 8 % slower on 2 threads, with μ = 0.5 (16 frictional ones) 3-6 % faster. Speed only, the
  /// same bits for any value (0: every pass of two contacts or more); not written into headers.
  int parallelContacts = 48;
  /// Narrow phases a loop needs before they are shared among `threads`: those of the pairs with
  /// a fast body in a pass, and each round of a batch of kept narrow phases (the step's start,
  /// FIXCONTACTCONSTRAINTS; KeptNarrowPhase::collideAll). Each is 0.1-2 µs (a one-axis check or
  /// the full test and clip), but its data (poses, the pair's kept answer, its manifold) was
  /// just written by the calling thread and must move to the other core's cache and back: 1024,
  /// measured on this project's 2-core machine, where the 1000-cube clump piling at e = 0
  /// (about 290 such narrow phases a pass) ran its passes 5-10 % slower with them shared, and
  /// the 10 000-cube clump landing (thousands a pass) 3-7 % faster. Speed only, the same bits
  /// for any value (0: every loop of one or more); not written into headers.
  int parallelNarrowPhases = 1024;
};

/// FIXCONTACTCONSTRAINTS (\thesis{§4.4}, \alg{A.2}).
struct FixContactParams {
  /// ε1, in units of ℓ: the upward nudge per iteration (\alg{FIXCONTACTCONSTRAINTS L7}). 2e-4 ℓ.
  double nudge = 2e-4;
  /// Documented slop, in units of ℓ: a pair counts as intersecting while its penetration
  /// exceeds this (\alg{FIXCONTACTCONSTRAINTS L6}). 1e-3 ℓ: 1 mm for unit boxes.
  /// DEVIATION(FIXCONTACTCONSTRAINTS L6): intersecting() has no tolerance in the pseudocode. The
  /// slop is also the depth at which a contact wakes a sleeper (\thesis{§4.5}, sleeping.hpp). With
  /// 0, the aligned towers and pyramids stay exactly as still (they never overlap), but boxes that
  /// come to rest a hair inside one another are nudged and woken: the shot base-10 pyramid ends its
  /// 10 s with 4 boxes asleep instead of 32 (measured).
  double slop = 1e-3;
  /// Most nudges per contact, a guard against a contact that cannot be fixed upwards: 500,
  /// a lift of 0.1 ℓ. A body may be nudged further, by as far as the step can have carried it
  /// into the contact (fixLiftLimit in fix_contact_constraints.hpp).
  int maxNudges = 500;
  /// Degrees: side contacts, whose normal is further than this from the vertical (|n_y| below
  /// its cosine), are fixed by moving both bodies apart, half a nudge each, when both are
  /// movable. 0 moves the upper body alone everywhere, as \alg{FIXCONTACTCONSTRAINTS L3-L5} does.
  /// DEVIATION(FIXCONTACTCONSTRAINTS L3-L5): with the upper body alone, a box squeezed between two
  /// side neighbours is pushed out of one into the other and back, and sinks into one of them step
  /// after step: the settling pile of 343 cubes at e = 0 ends 61 mm deep frictionless, shared
  /// 0.5 mm (the friction test "The settling pile of 343 cubes..."; with μ = 0.5 both end a few
  /// mm deep). Towers, pyramids and the die are unchanged bit for bit (their side contacts are
  /// within the slop).
  double sideShareAngleDeg = 45.0;
  /// On by default. When FIXCONTACTCONSTRAINTS L6-L7 lift the upper body of a frictional
  /// contact by more than stopLiftedOver times the distance gravity carries a body from rest in
  /// a step (g Δt²), the lifted body also gets the impulse of restitution 0 at the manifold's
  /// centroid against the lower body held (as FIX holds it), so that it stops approaching.
  /// Frictionless contacts, shared side contacts and smaller lifts (a resting or sliding body's
  /// own step of fall) are fixed as written either way.
  /// DEVIATION(FIXCONTACTCONSTRAINTS L6-L7): the pseudocode moves the body and leaves its
  /// velocity, which carries it back in the next step. Where the passes cannot stop a tall
  /// column that lands at once, that velocity grew by g Δt a step while FIX held the column up:
  /// a tower of eighteen layers of crossed planks (μ = 0.5) dropped from 2 cm apart gained up to
  /// 1480 J in 6 s and fell apart (with the stop: none gained, at rest within 2.2 s). On,
  /// frictional landings end far shallower (the 1000-cube clump at e = 0: 0.7 mm deep after 2 s
  /// instead of 134 mm), the clump on the ground sleeps about as early, and the 343-cube pile
  /// keeps fewer boxes asleep at 8 s (223 against 277 over three nudged starts); the impulse
  /// chapter ("Coulomb friction") has the measurements and the variants tried. Off: A.2 as
  /// written.
  bool stopLiftedApproach = true;
  /// In units of g Δt² (>= 0): the least lift of a body out of one contact that stopLiftedApproach
  /// stops. 4: from 2 the frictional clump on the ground slept later (every box asleep at a median
  /// 3.1 s over eight nudged starts, against 2.8 s from 4), from 8 the crossed-plank tower above
  /// still gained 20 J.
  double stopLiftedOver = 4.0;
};

/// Computational stability (\thesis{§4.5}): bodies that have come to rest sleep, cost nothing,
/// and act as immovable until something disturbs them. The thesis names the idea and gives no
/// rule; the rule and every threshold here are ours (sleeping.hpp states the rule).
/// Speeds are in units of g Δt, as in DampingParams: a resting contact seen through the gravity
/// trick of \alg{COLLIDE L1-L6} approaches at about 1 g Δt, so thresholds a few times that separate
/// a disturbance from the load of a body at rest.
struct SleepParams {
  /// Ablation switch: false keeps every body awake, \alg{A.2} as written.
  bool enabled = true;
  /// s: how long a body must have been still (stillByPose says what that is) before it falls
  /// asleep; turned into round(t / Δt) steps, at least 1. 0.5 s (30 steps at 60 Hz): DAMPENOBJECTS'
  /// zeroing and snap (\alg{DAMPENOBJECTS L14-L28}) can hold a slowly toppling box still for a few
  /// steps while gravity builds its velocity up again; half a second of stillness is well beyond
  /// that, and short enough that a settled pile stops costing almost at once.
  double timeToSleep = 0.5;
  /// What makes a step still for a body. true: the step left its pose bitwise unchanged,
  /// whatever momenta it keeps. A touched body's pose stays put only where DAMPENOBJECTS'
  /// snap (\alg{DAMPENOBJECTS L23-L28}) held it, which it does when the step would move it less
  /// than ε10 g Δt² and turn it less than ε11 g Δt² / ℓmax, over its support: the step's net
  /// motion, not its momenta, is what is judged. In a heap the contact passes give a resting
  /// box the same small angular momentum step after step (the gravity trick at corners that
  /// are not level, about 0.05 rad/s in the clump on the ground), which damping cannot zero and
  /// the snap keeps from moving it; such boxes, and everything resting on them, never slept.
  /// A body falling asleep has its momenta zeroed. false: the momenta must be exactly zero as
  /// well (the rule before; a clump of 100 on the ground then has 52 of 100 asleep at 15 s).
  bool stillByPose = true;
  /// g Δt: a sleeping body wakes when an awake body comes at it faster than this along the
  /// contact normal. 4 g Δt (0.65 m/s at 60 Hz, the speed of a drop from 2.2 cm): twice
  /// DampingParams::verticalVelocityEps, below which damping treats a body as resting, so a box
  /// settling onto a sleeping pile does not wake it and a real hit does.
  double wakeSpeed = 4.0;
  /// g Δt: a sleeping body wakes when the impulse COLLIDE would apply to it (computed as if it
  /// stayed immovable, an upper bound) would change the velocity of its contact point by more
  /// than this. 8 g Δt (1.3 m/s at 60 Hz): between equal boxes the restitution 0.9 makes this
  /// about wakeSpeed again, so the test matters for a heavy body pressing or hitting slowly on
  /// a light sleeping one, not for the weight of a few boxes at rest (about 1 g Δt each).
  double wakeImpulse = 8.0;
  /// Unitless, in (0, 1): a contact supports the upper of its two bodies when its normal,
  /// pointing from the other body to it, has a y component above this. 0.1 (the normal within
  /// about 84° of vertical): a box leaning on another counts as resting on it, boxes side by
  /// side on the ground (normals horizontal up to rounding) do not. Waking spreads along
  /// support from below, and a body sleeps only on sleeping or immovable supports.
  double supportNormalY = 0.1;
  /// Chatter detected from history (\thesis{§6.3.1}, the thesis' future work; the rule is ours,
  /// ChatterHistory in chatter_history.hpp states it): a body also falls asleep, its momenta
  /// zeroed, when over the last timeToSleep its pose stayed within an envelope and its kinetic
  /// energy did not grow, momenta or not, provided something supports it (and, as for every
  /// body, its supports sleep or are immovable). Off by default: \alg{A.2} and §4.5 as the
  /// thesis has them, bit for bit.
  bool chatterDetection = false;
  /// Unitless, > 0: the envelope of chatter detection, in units of the body's smallest half
  /// extent ℓ for its centre (and over its half diagonal, in rad, for its orientation;
  /// Envelope::of). The envelope filter's default (\thesis{§5.5}): a box that moves less than
  /// that in timeToSleep is seen as still by the filter too.
  double chatterEnvelope = kEnvelopeRadiusFraction;
};

/// Visual plausibility (\thesis{§4.2}, after Barzel, Hughes and Wood, "Plausible Motion
/// Simulation for Computer Graphics Animation", 1996): the normal of a high-speed collision is
/// turned by a small random rotation, so a die landing on its side does not bounce straight
/// up. Low-speed collisions and contacts are never perturbed: there the aim is to come to rest
/// (\thesis{§4.2}).
struct PlausibilityParams {
  /// Off by default: the thesis' scenes and every test reproduce without randomness, and a
  /// run with perturbation is an explicit choice. The seed is written into output headers
  /// either way.
  bool enabled = false;
  /// Seed of the stepper's Mersenne Twister (UniformRandom, core/random.hpp). The same seed
  /// gives bit-identical runs; 0 and 4357 give the same stream, as they did with GSL's.
  /// 1: a fixed default, so a run that turns perturbation on without a seed is reproducible.
  unsigned long seed = 1;
  /// m/s: only collisions whose bodies approach faster than this along the normal are
  /// perturbed. 2 m/s, the impact speed of a drop from 20 cm (v²/2g): a bounce the eye clearly
  /// sees, and 12 g Δt at 60 Hz, far above resting chatter (about 1 g Δt), the damping
  /// thresholds (at most 2 g Δt) and SleepParams::wakeSpeed, so a settling body is never
  /// kicked by it. In m/s rather than g Δt because it is a visual threshold, not a numerical
  /// one: it must not move when the step changes.
  double speedThreshold = 2.0;
  /// Degrees: the largest angle by which a normal is turned; directions are uniform over the
  /// spherical cap of this half-angle. 5°: enough that bounces visibly vary, small enough that
  /// a perturbed impulse stays within a few percent of the unperturbed one (cos 5° = 0.996).
  double maxAngleDeg = 5.0;
};

}  // namespace boxsim
