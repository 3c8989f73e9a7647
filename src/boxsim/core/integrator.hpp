/// \file
/// Time integration of the Witkin-Baraff state under gravity. The thesis integrates with
/// forward Euler (\thesis{§6.2}); semi-implicit (symplectic) Euler is the usual real-time
/// alternative and is offered beside it.
#pragma once

#include <string>
#include <vector>

#include "boxsim/core/world.hpp"

namespace boxsim {

/// Which explicit one-step scheme advances a body.
enum class Integrator {
  /// x += Δt v(t), q += Δt ½ ω(t) q, P += Δt m g: the scheme the thesis integrated with
  /// (\thesis{§6.2}). First order.
  ForwardEuler,
  /// P += Δt m g first, then x += Δt v(t+Δt); q advances with ω(t) as in ForwardEuler (with no
  /// torque L is constant, so the two differ only through R). First order, symplectic.
  SemiImplicitEuler,
};

/// "forward_euler" or "semi_implicit_euler".
std::string integratorName(Integrator integrator);
/// Parses the names of integratorName(); throws std::invalid_argument on an unknown name,
/// listing the valid ones.
Integrator parseIntegrator(const std::string& name);

/// Advances one body by dt (s, may be 0) under gravity (m/s^2) and no other force or torque;
/// the quaternion is renormalised after the step. Immovable bodies do not move.
void integrateBody(RigidBody& body, double dt, const Vec3& gravity, Integrator integrator);

/// Advances every body of the world by dt (s) except those whose entry in `held` is non-zero
/// (`held` is empty, holding none, or has one entry per body).
void integrateWorld(World& world, double dt, Integrator integrator,
                    const std::vector<char>& held = {});

}  // namespace boxsim
