#include "boxsim/core/integrator.hpp"

#include <stdexcept>

namespace boxsim {

std::string integratorName(Integrator integrator) {
  return enumName(kIntegratorNames, integrator);
}

Integrator parseIntegrator(const std::string& name) {
  return parseEnum(kIntegratorNames, name, "integrator");
}

void quaternionStep(Quat& q, const Vec3& omega, double dt) {
  const Quat w(0.0, omega.x(), omega.y(), omega.z());
  const Quat dq = w * q;
  q.coeffs() += (0.5 * dt) * dq.coeffs();
  q.normalize();
}

namespace {
/// The time derivative of a body's state (Witkin & Baraff, rigid body dynamics §2), with the
/// force and torque held constant.
struct StateRate {
  Vec3 x, P, L;
  Eigen::Vector4d q;
};

StateRate stateRate(const RigidBody& body, const BodyState& s, const Vec3& force,
                    const Vec3& torque) {
  const Mat3 R = s.q.normalized().toRotationMatrix();
  const Vec3 omega = R * body.IbodyInvDiag.asDiagonal() * R.transpose() * s.L;
  const Quat w(0.0, omega.x(), omega.y(), omega.z());
  return StateRate{body.invMass * s.P, force, torque, 0.5 * (w * s.q).coeffs()};
}

BodyState advanced(const BodyState& s, const StateRate& rate, double h) {
  BodyState t = s;
  t.x += h * rate.x;
  t.P += h * rate.P;
  t.L += h * rate.L;
  t.q.coeffs() += h * rate.q;
  return t;
}

void rungeKutta4(RigidBody& body, double dt, const Vec3& force, const Vec3& torque) {
  const BodyState s = body.s;
  const StateRate k1 = stateRate(body, s, force, torque);
  const StateRate k2 = stateRate(body, advanced(s, k1, 0.5 * dt), force, torque);
  const StateRate k3 = stateRate(body, advanced(s, k2, 0.5 * dt), force, torque);
  const StateRate k4 = stateRate(body, advanced(s, k3, dt), force, torque);
  const double sixth = dt / 6.0;
  body.s.x += sixth * (k1.x + 2.0 * k2.x + 2.0 * k3.x + k4.x);
  body.s.P += sixth * (k1.P + 2.0 * k2.P + 2.0 * k3.P + k4.P);
  body.s.L += sixth * (k1.L + 2.0 * k2.L + 2.0 * k3.L + k4.L);
  body.s.q.coeffs() += sixth * (k1.q + 2.0 * k2.q + 2.0 * k3.q + k4.q);
  body.s.q.normalize();
}

}  // namespace

void splitRotation(RigidBody& body, double dt) {
  if (body.immovable) return;
  // L in body coordinates. The flow of L_i² / 2I_i alone turns the body about its axis i at
  // the constant rate L_i / I_i: q ← q · rot(e_i, θ), and L_body ← rot(e_i, -θ) L_body, which
  // keeps L_i, |L_body| and the world L = R L_body. Symmetric composition: second order.
  Vec3 Lbody = body.s.q.conjugate() * body.s.L;
  Quat q = body.s.q;
  const auto turn = [&](int axis, double h) {
    const double theta = h * Lbody[axis] * body.IbodyInvDiag[axis];
    const Vec3 e = Vec3::Unit(axis);
    q = q * Quat(Eigen::AngleAxisd(theta, e));
    Lbody = Eigen::AngleAxisd(-theta, e) * Lbody;
  };
  turn(0, 0.5 * dt);
  turn(1, 0.5 * dt);
  turn(2, dt);
  turn(1, 0.5 * dt);
  turn(0, 0.5 * dt);
  body.s.q = q.normalized();
  body.updateDerived();
}

void integrateBody(RigidBody& body, double dt, const Vec3& gravity, Integrator integrator,
                   const Wrench& extra) {
  if (body.immovable || dt == 0.0) return;
  BodyState& s = body.s;
  const Vec3 force = body.mass * gravity + extra.force;
  const bool torque = extra.torque != Vec3::Zero();
  switch (integrator) {
    case Integrator::ForwardEuler:
      s.x += dt * body.v;
      quaternionStep(s.q, body.omega, dt);
      s.P += dt * force;
      // Gravity pulls at the centre of mass: only an extra torque changes L.
      if (torque) s.L += dt * extra.torque;
      break;
    case Integrator::RungeKutta4:
      rungeKutta4(body, dt, force, extra.torque);
      break;
    case Integrator::SemiImplicitEuler:
      s.P += dt * force;
      s.x += dt * (body.invMass * s.P);
      if (torque) {
        s.L += dt * extra.torque;
        quaternionStep(s.q, body.Iinv * s.L, dt);
      } else {
        quaternionStep(s.q, body.omega, dt);
      }
      break;
    case Integrator::SplitRotation:
      s.P += dt * force;
      s.x += dt * (body.invMass * s.P);
      if (torque) s.L += dt * extra.torque;
      splitRotation(body, dt);
      return;  // splitRotation updated everything derived
  }
  body.updateDerived();
}

void integrateWorld(World& world, double dt, Integrator integrator, const std::vector<char>& held,
                    const std::vector<Wrench>& extra) {
  for (std::size_t i = 0; i < world.bodies.size(); ++i)
    if (held.empty() || !held[i])
      integrateBody(world.bodies[i], dt, world.gravity, integrator,
                    extra.empty() ? Wrench{} : extra[i]);
}

}  // namespace boxsim
