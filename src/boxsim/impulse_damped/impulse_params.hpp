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

/// Constants of DAMPENOBJECTS (\alg{A.2}), in the scaled units of this file's introduction.
struct DampingParams {
  /// λ1, 1/s: rate at which the linear momentum of a body in contact decays, k1 = exp(-λ1 Δt)
  /// (\alg{DAMPENOBJECTS L4}). 3/s takes off 5 % per 60 Hz step: friction-like sliding that stops a
  /// 1 m/s slide in about a second, slow enough not to look glued.
  double linearRate = 3.0;
  /// λ2, 1/s: the same for angular momentum, k2 (\alg{DAMPENOBJECTS L5}).
  double angularRate = 3.0;
  /// Degrees: a box counts as y-axis aligned (a face perpendicular to gravity, \thesis{§5.3}) when
  /// one of its axes is within this angle of y (\alg{DAMPENOBJECTS L3}). 3° is below what the eye
  /// reads as tilted for a box at rest.
  double alignedAngleDeg = 3.0;
  /// ε3, g Δt: an aligned body whose vertical velocity is below this loses it
  /// (\alg{DAMPENOBJECTS L7-L8}). 2 g Δt: a resting box's chatter is about one g Δt.
  double verticalVelocityEps = 2.0;
  /// DEVIATION(DAMPENOBJECTS L6-L21, L23): the marks of a resting box (\thesis{§5.3}: a face
  /// perpendicular to gravity, small velocities) also fit a box that starts to tip off an edge
  /// from rest, and L7-L9 then take away, step after step, the velocity gravity gives it, and
  /// L18-L19 the small turn: a box whose centre lies past its support's edge stood for ever
  /// (measured: centres up to 0.5 m past the edge of a unit cube). With this on, L6-L21 and the
  /// snap of L23-L28 act only on a body whose centre of mass lies over its support region, the
  /// one-body test of geometric stability (\thesis{§5.4}, centreOverSupport: where its faces
  /// touch the top faces below, or its contact points with bodies below), read from the
  /// contacts the step starts from; and L10 turns a box flat only when the faces it lies on are
  /// level (SupportVerdict::level). Off: \alg{A.2} as written.
  bool supportTest = true;
  /// DEVIATION(DAMPENOBJECTS L2): "has had a contact interaction" marks a body for damping
  /// whatever it touched, so boxes that touch each other in free fall are slowed down as if they
  /// lay on the ground: the frictionless 1000-cube clump of \thesis{Fig. 6.7} falls at 3.6 m/s
  /// after 2 s instead of 19.6 m/s, and its highest cube is still 17 m up then: the damping
  /// takes from a group in flight momentum that nothing outside it acts on. With this on, only
  /// bodies that a chain of contacts joins to an immovable body (the ground, or a sleeper
  /// standing in for one) are damped, read from the contacts the step starts from
  /// (keepSupported): every body of a heap, stack or slide on the ground is damped as written,
  /// and a group in flight keeps its momentum until it lands. Off: \alg{A.2} as written.
  bool supportedOnly = false;
  /// λ3, 1/s: the angular momentum of such a body then decays at this rate (k3,
  /// \alg{DAMPENOBJECTS L9}): 20/s, a tenth of a second to stop rocking.
  double alignedAngularRate = 20.0;
  /// ε4, degrees per second: tiltTowardsYAxis turns an aligned body towards exact alignment by at
  /// most this rate (\alg{DAMPENOBJECTS L10}); 10°/s closes a 3° tilt in 0.3 s, too slowly to see.
  double tiltRateDegPerS = 10.0;
  /// ε5, g Δt: a linear velocity component below this is scaled by k5
  /// (\alg{DAMPENOBJECTS L12-L13}).
  double linearSmallEps = 1.0;
  /// k5, unitless: 0.5.
  double linearSmallFactor = 0.5;
  /// ε6, g Δt: a component still below this is zeroed (\alg{DAMPENOBJECTS L14-L15}).
  double linearZeroEps = 0.1;
  /// ε7, g Δt / ℓ: an angular velocity component below this is scaled by k7
  /// (\alg{DAMPENOBJECTS L16-L17}).
  double angularSmallEps = 1.0;
  /// k7, unitless: 0.5.
  double angularSmallFactor = 0.5;
  /// ε8, g Δt / ℓ: a component still below this is zeroed (\alg{DAMPENOBJECTS L18-L19}).
  double angularZeroEps = 0.1;
  /// ε9, g Δt / ℓ: a small non-negative spin about y is zeroed (\alg{DAMPENOBJECTS L20-L21}).
  double spinZeroEps = 1.0;
  /// \alg{DAMPENOBJECTS L20} zeroes a small spin about y only when it is non-negative. Nothing in
  /// \thesis{§5.3} tells one sense of turning from the other, so the sign test reads as a slip of
  /// the pseudocode: a box turning as slowly the other way keeps turning. False (the default) runs
  /// DAMPENOBJECTS L20 as written; true zeroes a small spin of either sign (the symmetric reading).
  /// The chapter page gives the measured effect.
  bool spinZeroSymmetric = false;
  /// ε10, in units of g Δt²: a body that would move less than this in the step stays where it
  /// was (\alg{DAMPENOBJECTS L26-L28}). 0.5 g Δt², half of what one step of gravity moves it.
  double positionSnapEps = 0.5;
  /// ε11, unitless quaternion distance per (g Δt² / ℓmax), ℓmax the body's largest half extent:
  /// the same for rotation, a turn that carries the ends of the body's longest axis about as far
  /// as ε10 moves it (quaternion distance is about half the angle).
  /// DEVIATION(DAMPENOBJECTS L26): ℓmax, not the ℓ of the other angular constants, so that a
  /// tall thin body starting to topple is not held upright (dampen_objects.cpp); the same for a
  /// cube.
  double rotationSnapEps = 0.5;
  /// DEVIATION(DAMPENOBJECTS L26-L28): the snap keeps a body's pose and leaves its velocities,
  /// which the next step's passes then work on. A body with Coulomb friction that its friction
  /// holds where it lies (SupportVerdict::held) has no such rates as k1 and k2 to take them
  /// (they are skipped for it: friction stands in), and a velocity can settle into a step that
  /// gives it back whole: in the resting pyramid of 210 cubes with μ = 0.5 and sleeping off,
  /// four rows kept a spin of 0.033 rad/s about the pyramid's depth axis for ever (just above
  /// ε8 after k7, every step), never turned, and reported 0.008 J of kinetic energy, and every
  /// step ran all five collision passes. With this on, such a body that the rests left with no
  /// linear momentum ends a step its snap held with no angular momentum either, at rest as
  /// static friction holds it: the pyramid's steps then run one collision pass, as the
  /// frictionless pyramid's do. Not a body still moving along: zeroing its linear momentum, or
  /// its spin whatever its linear momentum, left more boxes of the frictional 343-cube pile
  /// ending their steps falling (16 and 11 at worst against 5; friction_test's shock
  /// propagation case). Frictionless bodies are never touched. Off: as written.
  bool restHeld = true;
  /// DEVIATION(DAMPENOBJECTS L7-L9): a body with Coulomb friction that its friction holds
  /// (SupportVerdict::held) on supports that reach an immovable body through held bodies
  /// (SupportVerdict::grounded) loses any downward velocity, not only one below
  /// verticalVelocityEps: it cannot move down, and what it has is what the passes left. The
  /// passes do not settle a tall column in one step (each box ends it a little faster than the
  /// one under it); FIXCONTACTCONSTRAINTS lifts the boxes back by their positions alone, so the
  /// velocities grow by g Δt a step until they pass L7's bound, and from then on no rest catches
  /// them. Measured with μ = 0.5: after the shot, the upper rows of Fig. 6.6's base-20 pyramid
  /// ended every step falling at up to 2 m/s (each row about 0.1 m/s faster than the one under
  /// it) for 10 s, tested in every pass as fast bodies; with this on, none from the first
  /// half second, 1.05 ms a step over the benchmark's 8 s instead of 1.5. The block over the hole
  /// in scenes/weak/wall_hit.json crept 8 mm/s with 23 of 201 bricks asleep at 8 s; with this on,
  /// 0.2 mm/s and 139. Frictionless bodies are never touched. Off: L7's bound alone.
  bool restGrounded = true;
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
  /// Off by default. On: when FIXCONTACTCONSTRAINTS L6-L7 lift the upper body of a frictional
  /// contact by more than twice the distance gravity carries a body from rest in a step
  /// (2 g Δt²), the lifted body also gets the impulse of restitution 0 at the manifold's
  /// centroid against the lower body held (as FIX holds it), so that it stops approaching.
  /// Frictionless contacts, shared side contacts and lifts of up to 2 g Δt² (a resting or
  /// sliding body's own step of fall) are fixed as written either way.
  /// DEVIATION(FIXCONTACTCONSTRAINTS L6-L7) when on: the pseudocode moves the body and leaves
  /// its velocity, which carries it back in the next step. On, frictional landings and the broken
  /// wall (scenes/weak/wall_hit.json) end far shallower and calmer, but frictional heaps fall
  /// asleep later (the clump of Fig. 6.7 on the ground in five of eight nudged starts later
  /// than Bullet); the impulse chapter ("Coulomb friction") has the measurements and the
  /// variants tried.
  bool stopLiftedApproach = false;
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
