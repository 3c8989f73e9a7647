#include "boxsim/core/rigid_body.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace boxsim {

Vec3 boxInertiaDiagonal(const Vec3& halfExtents, double mass) {
  const Vec3 h2 = halfExtents.cwiseProduct(halfExtents);
  return (mass / 3.0) * Vec3(h2.y() + h2.z(), h2.x() + h2.z(), h2.x() + h2.y());
}

namespace {
void requirePositiveExtents(const Vec3& halfExtents) {
  if (!halfExtents.allFinite() || (halfExtents.array() <= 0.0).any())
    throw std::invalid_argument("box half extents must be finite and > 0 m");
}
}  // namespace

RigidBody RigidBody::box(const Vec3& halfExtents, double mass) {
  requirePositiveExtents(halfExtents);
  if (!std::isfinite(mass) || mass <= 0.0)
    throw std::invalid_argument("box mass must be finite and > 0 kg");
  RigidBody b;
  b.halfExtents = halfExtents;
  b.mass = mass;
  b.invMass = 1.0 / mass;
  b.IbodyInvDiag = boxInertiaDiagonal(halfExtents, mass).cwiseInverse();
  b.immovable = false;
  b.updateDerived();
  return b;
}

RigidBody RigidBody::immovableBox(const Vec3& halfExtents) {
  requirePositiveExtents(halfExtents);
  RigidBody b;
  b.halfExtents = halfExtents;
  b.mass = std::numeric_limits<double>::infinity();
  b.invMass = 0.0;
  b.IbodyInvDiag = Vec3::Zero();
  b.immovable = true;
  b.updateDerived();
  return b;
}

void RigidBody::updateDerived() {
  R = s.q.toRotationMatrix();
  Iinv = R * IbodyInvDiag.asDiagonal() * R.transpose();
  updateVelocities();
}

void RigidBody::setVelocity(const Vec3& velocity) {
  if (immovable) return;
  s.P = mass * velocity;
  updateDerived();
}

void RigidBody::setAngularVelocity(const Vec3& angularVelocity) {
  if (immovable) return;
  s.L = R * IbodyInvDiag.cwiseInverse().asDiagonal() * R.transpose() * angularVelocity;
  updateDerived();
}

double RigidBody::kineticEnergy() const {
  if (immovable) return 0.0;
  return 0.5 * s.P.dot(v) + 0.5 * s.L.dot(omega);
}

}  // namespace boxsim
