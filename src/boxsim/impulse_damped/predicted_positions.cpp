/// \file
/// integrateObjectPositions and revertToOriginalPositions (\alg{RESOLVECOLLISIONS L2}, \alg{RESOLVECOLLISIONS L6}).
#include "boxsim/impulse_damped/predicted_positions.hpp"

#include <cmath>

namespace boxsim {

void movePredicted(RigidBody& body, double dt, const Vec3& extraVelocity,
                   Integrator integrator) {
  body.s.x += dt * (body.v + extraVelocity);
  if (integrator == Integrator::SplitRotation) {
    splitRotation(body, dt);
    return;
  }
  quaternionStep(body.s.q, body.omega, dt);
  body.updateDerived();
}

SavedPoses predictPositions(World& world, double dt, const Vec3& extraVelocity,
                            Integrator integrator) {
  SavedPoses saved;
  predictPositions(world, dt, extraVelocity, integrator, saved);
  return saved;
}

void predictPositions(World& world, double dt, const Vec3& extraVelocity, Integrator integrator,
                      SavedPoses& saved) {
  saved.clear();
  saved.reserve(world.bodies.size());
  for (RigidBody& body : world.bodies) {
    saved.push_back({body.s.x, body.s.q, body.R, body.Iinv, body.immovable});
    if (!body.immovable) movePredicted(body, dt, extraVelocity, integrator);
  }
}

void integratePositions(World& world, double dt, Integrator integrator, SavedPoses& saved) {
  predictPositions(world, dt, Vec3::Zero(), integrator, saved);
  if (integrator == Integrator::SplitRotation) return;
  for (std::size_t i = 0; i < world.bodies.size(); ++i) {
    RigidBody& body = world.bodies[i];
    // A body whose principal inverse inertias are equal (a cube) turns without changing ½ L·ω.
    const Vec3& d = body.IbodyInvDiag;
    if (body.immovable || (d.x() == d.y() && d.y() == d.z())) continue;
    // ½ L·ω before the turn (I⁻¹ at the pose before) and after it; L itself was not changed.
    const double before = body.s.L.dot(saved[i].Iinv * body.s.L);
    const double after = body.s.L.dot(body.omega);
    if (!(after > before * (1.0 + 1e-9))) continue;
    body.s.L *= std::sqrt(before / after);
    body.updateVelocities();
  }
}

void restorePose(RigidBody& body, const SavedPose& pose) {
  body.s.x = pose.x;
  body.s.q = pose.q;
  if (pose.immovable != body.immovable) {
    body.updateDerived();
    return;
  }
  body.R = pose.R;
  body.Iinv = pose.Iinv;
  body.updateVelocities();  // P and L may have changed while the body stood elsewhere
}

void revertPositions(World& world, const SavedPoses& saved) {
  for (std::size_t i = 0; i < world.bodies.size(); ++i) {
    // predictPositions leaves immovable bodies where they are; with many sleeping bodies
    // standing in as immovable (§4.5), recomputing their derived values was most of the work.
    if (world.bodies[i].immovable) continue;
    restorePose(world.bodies[i], saved[i]);
  }
}

}  // namespace boxsim
