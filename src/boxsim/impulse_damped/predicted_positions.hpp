/// \file
/// integrateObjectPositions and revertToOriginalPositions of Alg. A.2: every movable body to
/// its predicted pose x + Δt v' for one pass of RESOLVECOLLISIONS or RESOLVECONTACTS (L2), and
/// back again (L6). DAMPENOBJECTS (L22) moves the bodies the same way, for good.
#pragma once

#include <vector>

#include "boxsim/core/integrator.hpp"
#include "boxsim/core/world.hpp"

namespace boxsim {

/// Whether a velocity includes the gravity of the coming step (the gravity argument of \alg{COLLIDE}).
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

/// Poses of every body, in body order, for putting them back (revertToOriginalPositions,
/// \alg{RESOLVECOLLISIONS L6}, \alg{RESOLVECONTACTS L6}).
using SavedPoses = std::vector<SavedPose>;

/// integrateObjectPositions (\alg{RESOLVECOLLISIONS L2}) for one movable body: x += Δt (v + extra), q turned by
/// Δt ω (quaternionStep; with Integrator::SplitRotation, by splitRotation instead); R, I⁻¹, v
/// and ω follow. Only those two integrators are accepted.
void movePredicted(RigidBody& body, double dt, const Vec3& extraVelocity,
                   Integrator integrator = Integrator::SemiImplicitEuler);

/// integrateObjectPositions (\alg{RESOLVECOLLISIONS L2}, \alg{RESOLVECONTACTS L2},
/// \alg{DAMPENOBJECTS L22}): moves every movable body to x + Δt (v + extra) and
/// turns it as movePredicted does with `integrator`; returns the poses before.
SavedPoses predictPositions(World& world, double dt, const Vec3& extraVelocity,
                            Integrator integrator = Integrator::SemiImplicitEuler);
/// predictPositions with the poses before written into `saved` (over what it held, its room
/// kept).
void predictPositions(World& world, double dt, const Vec3& extraVelocity, Integrator integrator,
                      SavedPoses& saved);

/// integrateObjectPositions for good (\alg{DAMPENOBJECTS L22}, and the plain impulse step's
/// last stage): predictPositions with no extra velocity, the poses before into `saved`; then a
/// body the explicit quaternion step turned to where its rotational energy ½ L·ω exceeds the
/// value before the turn (relatively, by more than 1e-9) has its angular momentum L scaled back
/// to that energy. With Integrator::SplitRotation, which keeps the energy itself, nothing more.
/// DEVIATION(DAMPENOBJECTS L22): the torque-free motion keeps ½ L·ω, but the explicit step
/// gains it on a tumbling body that is not a cube, and the more, the longer the body: a 4 m rod
/// of 0.1 m section tossed at 2 rad/s went from 3 J to 41 kJ of kinetic energy in its first
/// second (91 J to 11 MJ in all in 10 s) and never came to rest. Scaled back, |L| falls where
/// the turn would have raised the energy. A cube's ½ L·ω does not depend on its pose (rounding
/// aside, far below the tolerance): every cube keeps its bits.
void integratePositions(World& world, double dt, Integrator integrator, SavedPoses& saved);

/// Puts one body back to a saved pose, reusing the saved R and Iinv unless the body's
/// mobility changed since (then everything derived is recomputed); v and ω are recomputed.
void restorePose(RigidBody& body, const SavedPose& pose);

/// revertToOriginalPositions (\alg{RESOLVECOLLISIONS L6}, \alg{RESOLVECONTACTS L6}): puts back poses saved by predictPositions; momenta
/// are left as they are. Immovable bodies, which predictPositions does not move, are skipped.
void revertPositions(World& world, const SavedPoses& saved);

}  // namespace boxsim
