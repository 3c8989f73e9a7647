/// \file
/// Where each body stands in a pass of the once-per-step gathering
/// (once_per_step_gathering.hpp): at its current pose, or at its predicted pose of
/// integrateObjectPositions (\alg{RESOLVECOLLISIONS L2},
/// \alg{RESOLVECONTACTS L2}) when it is a
/// fast body or a fast body's slow partner. A predicted pose is worked out once and kept while
/// the body's momenta and velocities stay bitwise the same; the body itself goes there only
/// when one of its pairs touches, and comes back before COLLIDE.
#pragma once

#include <cstdint>
#include <vector>

#include "boxsim/collision/obb.hpp"
#include "boxsim/core/world.hpp"
#include "boxsim/impulse_damped/predicted_positions.hpp"
#include "boxsim/impulse_damped/step_bodies.hpp"

namespace boxsim {

/// The bodies' poses in the passes of a step.
class PassPoses {
 public:
  /// A body's predicted pose in a pass with what it was computed from. Between two passes of a
  /// step a body's current pose does not change, so while its momenta and velocities stay
  /// bitwise the same (no impulse of the passes reached it) its predicted pose does too and is
  /// copied instead of recomputed.
  struct PredictedPose {
    Vec3 P;               ///< the key: linear momentum at the current pose, kg m/s
    Vec3 L;               ///< the key: angular momentum at the current pose, kg m²/s
    Vec3 v;               ///< the key: velocity at the current pose, m/s
    Vec3 omega;           ///< the key: angular velocity at the current pose, rad/s
    Vec3 x;               ///< m, predicted
    Quat q;               ///< predicted
    Mat3 R;               ///< rotation matrix at the predicted pose
    Mat3 Iinv;            ///< world inverse inertia at the predicted pose
    Vec3 vPredicted;      ///< m/s, the velocity movePredicted leaves
    Vec3 omegaPredicted;  ///< rad/s, the angular velocity it leaves, ω = I⁻¹' L
    Vec3 lo;              ///< m, lower corner of the bounds at the predicted pose (obbBounds)
    Vec3 hi;              ///< m, upper corner of those bounds
    /// Identifies this pose (the stamp of a body standing at it); valid only when greater
    /// than the build stamp it is asked with.
    std::uint64_t stamp = 0;
  };

  /// Room for n bodies' predicted poses (kept across passes, forgotten by the build stamp).
  void resize(std::size_t n) { predicted_.resize(n); }
  /// A new pass: every body stands at its current pose.
  void startPass(std::size_t n);
  /// Makes body i's predicted pose what movePredicted would make of the body now, with
  /// `gravityStep` (m/s) over dt (s), unless the one kept since `buildStamp` has the same
  /// key; the body stays where it is.
  void prepare(const RigidBody& body, int i, double dt, const Vec3& gravityStep,
               std::uint64_t buildStamp, StampCounter& stamps);
  /// Fast body i stands at its predicted pose (prepare()) for this pass.
  void standFast(int i) { fastAtPredicted_[i] = 1; }
  /// Slow body i stands at its predicted pose (prepare()) for the narrow phase of its pairs
  /// with fast bodies in this pass.
  void standPartner(int i);
  /// Whether fast body i stands at its predicted pose in this pass (standFast()).
  bool fastAtPredicted(int i) const { return fastAtPredicted_[i] != 0; }
  /// Whether slow body i stands at its predicted pose in this pass (standPartner()).
  bool partnerAtPredicted(int i) const { return partnerAtPredicted_[i] != 0; }
  /// Whether body i stands at its predicted pose in this pass, as a fast body or a partner.
  bool atPredicted(int i) const { return fastAtPredicted_[i] || partnerAtPredicted_[i]; }
  /// Names the pose body i stands at in this pass: its predicted pose's stamp when
  /// atPredicted, else `buildStamp`, the stamp of the current poses.
  std::uint64_t stamp(int i, std::uint64_t buildStamp) const {
    return atPredicted(i) ? predicted_[i].stamp : buildStamp;
  }
  /// The slow partners standing at their predicted poses in this pass, in the order stood.
  const std::vector<int>& partners() const { return partners_; }
  /// Body i's predicted pose, as prepare() left it.
  const PredictedPose& predicted(int i) const { return predicted_[i]; }
  /// Body i's box where it stands in this pass: at its predicted pose (atPredicted), moved
  /// there or not, else where it is.
  /// Inline: the narrow phase of every pair with a fast body asks it for both boxes in every
  /// pass.
  [[gnu::always_inline]] Obb box(const World& world, int i) const {
    const RigidBody& body = world.bodies[i];
    if (!atPredicted(i)) return Obb::of(body);
    return Obb{predicted_[i].x, predicted_[i].R, body.halfExtents};
  }
  /// Moves body i to its predicted pose of this pass, remembering where it stood, if it
  /// stands there for this pass (atPredicted) and is not there yet.
  void moveToPredicted(World& world, int i);
  /// Puts body i back where it stood before moveToPredicted, with its velocities recomputed
  /// exactly as they were; a body that never went only gets the velocities putting it back
  /// would recompute.
  void putBack(World& world, int i);
  /// The pass is over (revertToOriginalPositions happened in putBack()).
  void endPass() {
    fastAtPredicted_.clear();
    displaced_.clear();
  }

 private:
  std::vector<PredictedPose> predicted_;  ///< per body: its last predicted pose in the step
  SavedPoses saved_;                      ///< poses before the pass, of the bodies displaced_
  std::vector<char> fastAtPredicted_;     ///< per body: a fast body at its predicted pose
  std::vector<char> partnerAtPredicted_;  ///< per body: a slow partner at its predicted pose
  std::vector<char> displaced_;  ///< per body: actually moved there; saved_ holds where it stood
  std::vector<int> partners_;    ///< this pass: the slow partners standing at predicted poses
};

}  // namespace boxsim
