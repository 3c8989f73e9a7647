#include "boxsim/core/newtonian_impulse.hpp"

namespace boxsim {

double relativeNormalVelocity(const RigidBody& a, const RigidBody& b, const Vec3& ra,
                              const Vec3& rb, const Vec3& n) {
  return n.dot((b.v + b.omega.cross(rb)) - (a.v + a.omega.cross(ra)));
}

double relativeNormalVelocity(const RigidBody& a, const RigidBody& b, const Vec3& p,
                              const Vec3& n) {
  return relativeNormalVelocity(a, b, Vec3(p - a.s.x), Vec3(p - b.s.x), n);
}

double applyNewtonianImpulse(RigidBody& a, RigidBody& b, const Vec3& p, const Vec3& n,
                             double restitution) {
  return applyNewtonianImpulse(a, b, Vec3(p - a.s.x), Vec3(p - b.s.x), n, restitution);
}

double applyNewtonianImpulse(RigidBody& a, RigidBody& b, const Vec3& ra, const Vec3& rb,
                             const Vec3& n, double restitution) {
  const double vMinus = relativeNormalVelocity(a, b, ra, rb, n);
  if (vMinus >= 0.0) return 0.0;
  const double denominator = a.invMass + b.invMass + rotationalInverseMass(a.Iinv, ra, n) +
                             rotationalInverseMass(b.Iinv, rb, n);
  if (denominator <= 0.0) return 0.0;
  const double j = -(1.0 + restitution) * vMinus / denominator;
  const Vec3 impulse = j * n;
  if (!a.immovable) {
    a.s.P -= impulse;
    a.s.L -= ra.cross(impulse);
    a.updateVelocities();
  }
  if (!b.immovable) {
    b.s.P += impulse;
    b.s.L += rb.cross(impulse);
    b.updateVelocities();
  }
  return j;
}

}  // namespace boxsim
