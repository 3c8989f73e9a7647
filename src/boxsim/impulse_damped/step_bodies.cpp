/// \file
/// The bodies of a step of the once-per-step gathering and their motion in a pass.
#include "boxsim/impulse_damped/step_bodies.hpp"

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/collision/obb.hpp"

namespace boxsim {

void StepBodies::build(const World& world, const Vec3& gravityStep, double dt, double exactReach,
                       bool anchoredNow, const std::vector<char>* touching) {
  const std::size_t n = world.bodies.size();
  anchored = anchoredNow;
  anchorVelocity.assign(anchored ? n : 0, Vec3::Zero());
  anchorOmega.assign(anchored ? n : 0, Vec3::Zero());
  anchorDt = dt;
  anchorScale = 1.0;
  anchorSlack.assign(n, 0.0);
  anchorMoved.assign(n, 0);
  passOmega.resize(n);
  immovable.assign(n, 0);
  if (fast.size() != n) fast.assign(n, 0);
  lo.resize(n);
  hi.resize(n);
  reach.resize(n);
  halfDiagonal.resize(n);
  slowReach.resize(n);
  passVelocity.resize(n);
  passTurn.resize(n);
  passSpin.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const RigidBody& body = world.bodies[i];
    reach[i] = obbReach(Obb::of(body));
    boundsAbout(body.s.x, reach[i], 0.0, lo[i], hi[i]);
    immovable[i] = static_cast<char>(body.immovable);
    halfDiagonal[i] = body.halfExtents.norm();
    slowReach[i] = exactReach * body.halfExtents.minCoeff();
    const bool fastNow = !body.immovable &&
                         passReach(body.v, body.omega, gravityStep, dt, halfDiagonal[i]) >
                             slowReach[i];
    // With an anchor a body fast now is anchored where the first pass predicts it, and is
    // slow while the passes' predictions stay near there; a slow one stays anchored where it
    // stands.
    if (anchored && fastNow && (!touching || (*touching)[i])) {
      anchorVelocity[i] = body.v + gravityStep;
      anchorOmega[i] = body.omega;
      anchorSlack[i] = dt * anchorOmega[i].norm() * halfDiagonal[i];
      anchorMoved[i] = 1;
    }
    setPass(body, static_cast<int>(i), gravityStep, dt);
    if (fastNow && !anchorMoved[i]) fast[i] = 1;
  }
}

bool StepBodies::sameMobility(const World& world) const {
  if (immovable.size() != world.bodies.size()) return false;
  for (std::size_t i = 0; i < world.bodies.size(); ++i)
    if (static_cast<char>(world.bodies[i].immovable) != immovable[i]) return false;
  return true;
}

void StepBodies::setPass(const RigidBody& body, int i, const Vec3& gravityStep, double dt) {
  passVelocity[i] = body.immovable ? body.v : Vec3(body.v + gravityStep);
  passOmega[i] = body.omega;
  if (anchored) {
    // The anchor moved by Δt_0 v'_0 and turned by Δt_0 ω_0: per second of this pass' Δt.
    if (dt != passDt) anchorScale = anchorDt / dt;
    passVelocity[i] -= anchorScale * anchorVelocity[i];
    passOmega[i] -= anchorScale * anchorOmega[i];
  }
  passSpin[i] = passOmega[i].norm();
  passTurn[i] = dt * passSpin[i] * halfDiagonal[i];
  passDt = dt;
}

}  // namespace boxsim
