/// \file
/// Constants of DAMPENOBJECTS (\alg{A.2}, \thesis{§5.2}, \thesis{§5.3}): the damping rates k1…k3,
/// the small-velocity tests and the snap, and the deviations that bound its rests. The rest of
/// the damped step's parameters, and the units every constant is given in, are in
/// impulse_params.hpp.
#pragma once

namespace boxsim {

/// Constants of DAMPENOBJECTS (\alg{A.2}), in the scaled units of impulse_params.hpp's introduction.
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

}  // namespace boxsim
