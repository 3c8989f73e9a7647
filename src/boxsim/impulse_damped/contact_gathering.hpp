/// \file
/// gatherCollisions of RESOLVECOLLISIONS and RESOLVECONTACTS (\alg{A.2} L2-L3 and L6 of either):
/// the contacts between bodies moved to their predicted positions x + Δt v'. Two ways to find
/// them, chosen by ImpulseParams::gathering:
///
/// - EveryPass, \alg{A.2} as written (and Guendelman et al. 2003, §7): every pass moves each
///   body to its predicted pose, runs the broad and narrow phase there, and moves it back.
/// - OncePerStep, the default: one narrow phase per step at the current poses, with a margin
///   widened by how far each body can move in the step (its reach, Δt (|v'| + |ω| ρ) with ρ the
///   half diagonal). Each pass then treats two kinds of body differently:
///   - a body whose reach is above ImpulseParams::exactReach is moved to its predicted pose, as
///     written, and each cached pair it belongs to gets its narrow phase there;
///   - a pair of two slower bodies stays where it is, and the depth of each cached contact point
///     at the predicted poses is a Taylor expansion in the displacement:
///
///         depth' = depth + n · (d_a(p) - d_b(p)),
///         d(p) = Δt (v' + ω × r) + ½ Δt² ω × (ω × r),   r = p - x,
///
///     exact for translation and off by O(Δt³ |ω|³ ρ / 6) for rotation, below 1e-7 ℓ under the
///     default exactReach. A contact joins the pass when one of its points has depth' > -margin,
///     the criterion of EveryPass; its point is the mean of those points.
///
///   Speculative contacts (Catto, "Speculative Contacts", GDC 2013) make the same prediction.
///   On a resting stack every body is slow and a step costs one narrow phase instead of one
///   per pass (16 with the default iterations), which was most of its cost; an impact still
///   gets the exact narrow phase, pass after pass, for the pairs of the bodies that move fast.
///
///   DEVIATION(A.2 RESOLVECOLLISIONS L2-L3, RESOLVECONTACTS L2-L3): slow bodies are not moved to
///   their predicted poses. The cache is rebuilt whenever a body's reach outgrows its widened
///   margin, or a body's mobility changes (a sleeping body wakes, \thesis{§4.5}), so no pair
///   the exact prediction would find is missed. What differs: a slow pair's contact depth by
///   the rotation error above, its impulse's lever arms by at most the reach of its bodies
///   (exactReach ℓ, 1 % of the box's size by default), and a fast body's partner, if slow,
///   stands where it is rather than up to exactReach ℓ further on.
#pragma once

#include <array>
#include <vector>

#include "boxsim/collision/contact.hpp"
#include "boxsim/core/world.hpp"
#include "boxsim/impulse_damped/contact_normal.hpp"
#include "boxsim/impulse_damped/impulse_params.hpp"

namespace boxsim {

/// Whether a velocity includes the gravity of the coming step (\alg{A.2} COLLIDE's argument).
enum class GravityMode {
  VelocityNoGravity,    ///< v as it is
  VelocityPlusGravity,  ///< v + g Δt: what the body will have once gravity is integrated
};

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
/// Δt ω (one explicit quaternion step, renormalised); R, I⁻¹, v and ω follow.
void movePredicted(RigidBody& body, double dt, const Vec3& extraVelocity);

/// integrateObjectPositions of \alg{A.2}: moves every movable body to x + Δt (v + extra) and
/// turns it by Δt ω (one explicit quaternion step, renormalised); returns the poses before.
SavedPoses predictPositions(World& world, double dt, const Vec3& extraVelocity);

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
  /// ImpulseContact per pair in a fixed order. EveryPass leaves the bodies at their predicted
  /// poses until end(); OncePerStep leaves them where they are. The result stays valid until
  /// the next call.
  std::vector<ImpulseContact>& begin(World& world, double dt, GravityMode predict,
                                     double margin);
  /// \alg{A.2} L6 of a pass: revertToOriginalPositions (EveryPass); momenta stay as changed.
  void end(World& world);
  /// Ends the step: the closest faces seen become the previous step's, and the cached contacts
  /// are dropped (the step moves the bodies).
  void endStep();

  /// The normal model and its memory, for contacts gathered outside the passes.
  ContactNormalTracker& normals() { return normals_; }
  /// Narrow phases run since construction (OncePerStep: cache builds), for tests and benches.
  long narrowPhases() const { return narrowPhases_; }

 private:
  /// One manifold point with the parts of its predicted depth that do not change in a step.
  struct CachedPoint {
    Vec3 position;     ///< m, world, at the current pose
    double depth;      ///< m, along the manifold normal at the current pose
    Vec3 ra;           ///< p - x_a, m
    Vec3 rb;           ///< p - x_b, m
  };
  /// One cached pair: the contact as COLLIDE will see it and its manifold's points.
  struct CachedPair {
    ImpulseContact contact;        ///< bodies and the model's normal
    Vec3 manifoldNormal;           ///< unit, a to b: the direction the depths are measured in
    std::array<CachedPoint, 4> points;
    int count;
  };

  /// m: how far body i can move in a pass with its current velocities, Δt (|v'| + |ω| ρ).
  double reach(const RigidBody& body, const Vec3& gravityStep, double dt) const;
  /// Whether the cache still holds every pair a pass with these velocities could touch.
  bool cacheCovers(const World& world, const Vec3& gravityStep, double dt) const;
  void buildCache(World& world, const Vec3& gravityStep, double dt, double margin);

  ImpulseParams params_;
  ContactNormalTracker normals_;
  std::vector<ImpulseContact> contacts_;
  SavedPoses saved_;             ///< poses before the pass, of the bodies in moved_
  std::vector<char> moved_;      ///< per body: moved to its predicted pose for this pass
  bool cached_ = false;
  std::vector<CachedPair> pairs_;
  std::vector<double> widening_;  ///< m per body: the reach the cache allows for
  std::vector<char> immovable_;   ///< each body's mobility when the cache was built
  double cacheMargin_ = 0.0;
  long narrowPhases_ = 0;
};

}  // namespace boxsim
