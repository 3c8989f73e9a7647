/// \file
/// Continuous collision detection for fast bodies in damped integration: the first time of
/// impact within a step, found by conservative advancement along the motion the step predicts
/// (\alg{A.2} integrateObjectPositions: x + τ (v + g Δt), q turned by τ ω), so the step can be
/// split there (DampedIntegrationStepper, ContinuousCollisionParams).
///
/// \thesis{§3.2} assumes that objects cannot intersect and separate within one step, and
/// \thesis{§5.1} names swept volumes as the cure for fast bodies. A.2 gathers contacts only at
/// the predicted pose x + Δt v': a unit cube at 150 m/s moves 2.5 m in a 60 Hz step, ends its
/// prediction inside or beyond a 1 m thick ground, and passes through it.
///
/// Conservative advancement (Mirtich's timewarp paper uses it for the same purpose): along the
/// predicted motion no point of a body moves faster than s = |v'| + |ω| ρ (ρ the half diagonal;
/// the explicit quaternion step turns by 2 atan(|ω| τ / 2), never faster than |ω|), and the
/// separating-axis gap never exceeds the distance of two boxes, so advancing τ by
/// gap / (s_a + s_b) never passes a contact.
#pragma once

#include "boxsim/core/world.hpp"

namespace boxsim {

/// Continuous collision detection for fast bodies (off by default: the thesis' figures are
/// made without it).
struct ContinuousCollisionParams {
  /// false: \alg{A.2} as written, contacts only at the predicted pose.
  bool enabled = false;
  /// In units of ℓ (the body's smallest half extent): a body is fast when it moves farther
  /// than this in a step, Δt (|v + g Δt| + |ω| ρ). 0.5 ℓ: beyond half its thickness a predicted
  /// pose can overlap a body by more than half a box, where the separating axis may point
  /// the wrong way; slower bodies are left to A.2.
  double fastReach = 0.5;
  /// Most pieces a step is split into; the shortest piece is Δt / maxSubsteps. 16: a unit cube
  /// at 150 m/s moves 0.16 m per piece at 60 Hz, a third of its half extent.
  int maxSubsteps = 16;
};

/// The first time (s, in (0, dt]) at which a fast movable body (ContinuousCollisionParams::
/// fastReach) comes within `margin` (m) of another body, both moving as the step predicts them
/// (file comment), or dt when none does. A pair already within the margin at τ = 0 gives 0
/// when its centres approach along the separating axis (an impact under way: the caller takes
/// its shortest piece) and is skipped otherwise (a contact). Deterministic: pairs in
/// broad-phase order.
double firstTimeOfImpact(const World& world, double dt, double margin,
                         const ContinuousCollisionParams& params);

}  // namespace boxsim
