/// \file
/// What the once-per-step gathering (once_per_step_gathering.hpp) keeps of every body for a
/// step, and how each body moves in the current pass of \alg{RESOLVECOLLISIONS} or
/// \alg{RESOLVECONTACTS}: its predicted velocity v', how far it reaches, whether it is slow.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "boxsim/core/world.hpp"

namespace boxsim {

/// Hands out increasing stamps that name a state (a pose, a set of bounds, a build of the
/// cache) so that equal stamps mean the same state. One counter serves every part of a
/// gathering, so that stamps of different kinds never coincide.
struct StampCounter {
  std::uint64_t last = 0;  ///< the last stamp handed out
  /// A stamp greater than every one handed out before.
  std::uint64_t next() { return ++last; }
};

/// m: how far a body with velocity v (m/s) and spin ω (rad/s) moves in a pass of Δt = dt s,
/// Δt (|v + g Δt| + |ω| ρ), with g Δt = `gravityStep` (m/s) and ρ its half diagonal (m).
inline double passReach(const Vec3& v, const Vec3& omega, const Vec3& gravityStep, double dt,
                        double halfDiagonal) {
  return dt * ((v + gravityStep).norm() + omega.norm() * halfDiagonal);
}

/// The bodies as the once-per-step gathering sees them in a step: what was taken when its
/// cache was built, and each body's motion in the current pass. Indices are body indices.
struct StepBodies {
  std::vector<char> immovable;      ///< each body's mobility when the cache was built
  /// Fast when the cache was built (reach above slowReach), so not cached as a slow body;
  /// a body once fast stays fast until endStep().
  std::vector<char> fast;
  std::vector<double> halfDiagonal;  ///< m, |h|, the ρ of passReach
  std::vector<double> slowReach;     ///< m, ImpulseParams::exactReach ℓ: the slow bodies' bar
  std::vector<Vec3> lo;              ///< m, lower corners of the bounds at the current poses
  std::vector<Vec3> hi;              ///< m, upper corners of those bounds (obbBounds, margin 0)
  std::vector<Vec3> reach;           ///< m, the half widths of those bounds (obbReach)
  std::vector<Vec3> passVelocity;    ///< m/s, v' of this pass: v + g Δt when movable
  std::vector<double> passTurn;      ///< m, Δt |ω| ρ of this pass
  std::vector<double> passSpin;      ///< rad/s, |ω| of this pass
  /// rad/s, the ω of this pass the slow pairs' prediction turns a body by (ω, or ω - ω_0
  /// with a predicted anchor); passSpin is its norm.
  std::vector<Vec3> passOmega;
  /// With a predicted anchor (ImpulseParams::predictedAnchor): where the cache's poses stand,
  /// as the velocity v'_0 = v_0 + g Δt_0 (m/s) that moves the body there from its current pose
  /// in Δt_0 = anchorDt; zero for a body anchored where it stands. Empty without.
  std::vector<Vec3> anchorVelocity;
  std::vector<Vec3> anchorOmega;  ///< rad/s, the ω_0 that turns it there in Δt_0
  double anchorDt = 0.0;          ///< s, the Δt_0 of the anchor
  double anchorScale = 1.0;       ///< Δt_0 / Δt of the pass (setPass)
  /// m, Δt_0 |ω_0| ρ: how far the anchor's turn moves a point of the body, so its bounds at
  /// the anchor lie within those about the anchored centre with the current half widths
  /// widened by this (0 without an anchor).
  std::vector<double> anchorSlack;
  /// With a predicted anchor: whether the body's anchor is its predicted pose (it was fast
  /// when built) rather than where it stands.
  std::vector<char> anchorMoved;
  bool anchored = false;  ///< built with a predicted anchor
  double passDt = 0.0;               ///< s, the Δt of the pass values

  /// Takes every body as it stands (mobility, bounds, half diagonal, slow bar, pass motion)
  /// and marks fast each movable body whose passReach exceeds exactReach (units of the
  /// smallest half extent ℓ).
  /// With `anchored` (ImpulseParams::predictedAnchor) no body is fast when built: the anchor
  /// is where the first pass predicts it, and a body turns fast only when a pass' prediction
  /// moves away from there by more than exactReach ℓ (anchorVelocity and anchorOmega are taken).
  /// `touching`, when given (one flag per body), limits the anchor to the bodies it flags.
  void build(const World& world, const Vec3& gravityStep, double dt, double exactReach,
             bool anchored = false, const std::vector<char>* touching = nullptr);
  /// Whether the bodies were taken with the mobility each body of `world` has now.
  bool sameMobility(const World& world) const;
  /// Records body i's motion in this pass from its velocities (v' = v + g Δt when movable);
  /// with an anchor, less the anchor's: v' - (Δt_0 / Δt) v'_0 and ω - (Δt_0 / Δt) ω_0.
  void setPass(const RigidBody& body, int i, const Vec3& gravityStep, double dt);
  /// Whether bodies a and b move together in this pass: Δt |v'_a - v'_b| plus both turns
  /// within the slow bar of the smaller body (ImpulseParams::pairReach).
  bool movingTogether(int a, int b) const {
    return passDt * (passVelocity[a] - passVelocity[b]).norm() + passTurn[a] + passTurn[b] <=
           std::min(slowReach[a], slowReach[b]);
  }
  /// The step is over: no body is fast any more.
  void endStep() { fast.clear(); }
};

}  // namespace boxsim
