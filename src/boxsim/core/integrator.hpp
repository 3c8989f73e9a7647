/// \file
/// Time integration of the Witkin-Baraff state under gravity. The thesis integrates with
/// forward Euler (\thesis{§6.2}); semi-implicit (symplectic) Euler is the usual real-time
/// alternative and is offered beside it.
#pragma once

#include <string>
#include <vector>

#include "boxsim/core/enum_names.hpp"
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
  /// The classical fourth-order Runge-Kutta method on the whole state (x, q, P, L), forces
  /// held constant over the step, q renormalised at the end. Exact up to rounding for motion
  /// under constant force (a polynomial of degree 2 in time); the §6.2 footnote asks whether
  /// such a method would follow a rotating group better.
  RungeKutta4,
  /// SemiImplicitEuler for x and P (and L with a torque), and a rotation step that keeps the
  /// torque-free body's |L| exactly and its kinetic energy without drift: the symmetric
  /// splitting of the free rigid body into rotations about its principal axes (Dullweber,
  /// Leimkuhler and McLachlan, "Symplectic splitting methods for rigid body molecular
  /// dynamics", J. Chem. Phys. 107, 1997, §III; McLachlan 1993): turns about body axes 0, 1,
  /// 2, 1, 0 for Δt/2, Δt/2, Δt, Δt/2, Δt/2, each the exact flow of one term L_i² / 2I_i of the
  /// energy. Second order, time-reversible; q stays a product of unit quaternions. The
  /// explicit quaternion step of the Euler schemes gains energy on a body spinning near its
  /// intermediate axis (417 % in 10 s at 60 Hz, core_test.cpp).
  SplitRotation,
};

/// The names of the integrators.
inline constexpr EnumNames<Integrator, 4> kIntegratorNames{{
    {Integrator::ForwardEuler, "forward_euler"},
    {Integrator::SemiImplicitEuler, "semi_implicit_euler"},
    {Integrator::RungeKutta4, "runge_kutta_4"},
    {Integrator::SplitRotation, "split_rotation"},
}};

/// "forward_euler", "semi_implicit_euler", "runge_kutta_4" or "split_rotation".
std::string integratorName(Integrator integrator);
/// Parses the names of integratorName(); throws std::invalid_argument on an unknown name,
/// listing the valid ones.
Integrator parseIntegrator(const std::string& name);

/// A force and torque held constant over an integration interval, applied besides gravity.
struct Wrench {
  Vec3 force = Vec3::Zero();   ///< N, through the centre of mass
  Vec3 torque = Vec3::Zero();  ///< N m, about the centre of mass
};

/// One explicit step of dq/dt = ½ [0, ω] q (Witkin and Baraff, "Physically based modeling",
/// rigid body dynamics, eq. 4-2) over dt (s) with ω (rad/s, world) held, then q renormalised:
/// the rotation of ForwardEuler, SemiImplicitEuler and of integrateObjectPositions (\alg{A.2}).
void quaternionStep(Quat& q, const Vec3& omega, double dt);

/// Turns a movable body by one step of dt (s) with its angular momentum L held, as
/// Integrator::SplitRotation does (the file's splitting), and updates everything derived.
void splitRotation(RigidBody& body, double dt);

/// Advances one body by dt (s, may be 0) under gravity (m/s^2) and `extra` (constant over dt;
/// none by default); the quaternion is renormalised after the step. Immovable bodies do not
/// move. With a torque, ForwardEuler turns q with ω(t) and then adds Δt τ to L;
/// SemiImplicitEuler adds Δt τ to L first and turns q with ω = I⁻¹(t) L(t+Δt); SplitRotation
/// adds Δt τ to L first and then turns q by splitRotation; RungeKutta4 integrates ẋ = P/m,
/// q̇ = ½ ω q with ω = I⁻¹(q) L, Ṗ = m g + F, L̇ = τ.
void integrateBody(RigidBody& body, double dt, const Vec3& gravity, Integrator integrator,
                   const Wrench& extra = {});

/// Advances every body of the world by dt (s) except those whose entry in `held` is non-zero
/// (`held` is empty, holding none, or has one entry per body). `extra` is empty (gravity only)
/// or holds one wrench per body, constant over dt.
void integrateWorld(World& world, double dt, Integrator integrator,
                    const std::vector<char>& held = {}, const std::vector<Wrench>& extra = {});

}  // namespace boxsim
