#include "boxsim/core/integrator.hpp"

#include <stdexcept>

namespace boxsim {

std::string integratorName(Integrator integrator) {
  switch (integrator) {
    case Integrator::ForwardEuler: return "forward_euler";
    case Integrator::SemiImplicitEuler: return "semi_implicit_euler";
  }
  return "unknown";
}

Integrator parseIntegrator(const std::string& name) {
  if (name == "forward_euler") return Integrator::ForwardEuler;
  if (name == "semi_implicit_euler") return Integrator::SemiImplicitEuler;
  throw std::invalid_argument("unknown integrator '" + name +
                              "'; use forward_euler or semi_implicit_euler");
}

namespace {
// dq/dt = ½ [0, ω] q (Witkin & Baraff, eq. 4-2), one explicit step, then renormalised.
void rotate(BodyState& s, const Vec3& omega, double dt) {
  const Quat w(0.0, omega.x(), omega.y(), omega.z());
  Quat dq = w * s.q;
  s.q.coeffs() += (0.5 * dt) * dq.coeffs();
  s.q.normalize();
}
}  // namespace

void integrateBody(RigidBody& body, double dt, const Vec3& gravity, Integrator integrator,
                   const Wrench& extra) {
  if (body.immovable || dt == 0.0) return;
  BodyState& s = body.s;
  const Vec3 force = body.mass * gravity + extra.force;
  const bool torque = extra.torque != Vec3::Zero();
  switch (integrator) {
    case Integrator::ForwardEuler:
      s.x += dt * body.v;
      rotate(s, body.omega, dt);
      s.P += dt * force;
      // Gravity pulls at the centre of mass: only an extra torque changes L.
      if (torque) s.L += dt * extra.torque;
      break;
    case Integrator::SemiImplicitEuler:
      s.P += dt * force;
      s.x += dt * (body.invMass * s.P);
      if (torque) {
        s.L += dt * extra.torque;
        rotate(s, body.Iinv * s.L, dt);
      } else {
        rotate(s, body.omega, dt);
      }
      break;
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
