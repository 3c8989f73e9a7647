/// \file
/// The integrators \thesis{§6.2} compares, or asks about, for a group held together by
/// sticking contact forces, and one remedy. Each advances every movable body of a scene by Δt
/// given the sticking forces of sticking_forces.hpp.
///
/// The thesis' point: the forces are exact for one instant, but a body that turns about an
/// exterior point needs a force that turns with it; held constant over the step (forward
/// Euler), the body leaves the circle, and the contact points drift apart or into each other.
/// Its footnote asks whether Runge–Kutta would help.
#pragma once

#include <string>
#include <vector>

#include "boxsim/core/enum_names.hpp"
#include "boxsim/exterior_rotation/sticking_forces.hpp"

namespace boxsim {

/// How a scene of sticking bodies is advanced by one step.
enum class StickingMethod {
  /// The thesis' scheme: forces solved at t, x += Δt v(t), q turned by ω(t), P, L += Δt F, τ
  /// (core's Integrator::ForwardEuler with the contact Wrench). First order.
  ForwardEuler,
  /// Forces at t, P, L updated first and the pose moved with the new velocities (core's
  /// Integrator::SemiImplicitEuler). First order.
  SemiImplicitEuler,
  /// Classical RK4 on the whole state with the forces solved at t and held constant over the
  /// step (core's Integrator::RungeKutta4): what "use Runge–Kutta" gives when the contact
  /// solve stays once per step.
  RungeKutta4ConstantForces,
  /// Classical RK4 with the sticking forces solved again at each of its four stages: RK4 on
  /// the true equations of motion (the §6.2 footnote's question answered honestly). Four
  /// solves per step.
  RungeKutta4ResolvedForces,
  /// The screw-motion update (our remedy): each body's spatial twist (ω, v_s = v − ω × x, the
  /// velocity of the body-fixed point at the world origin) advanced with Euler from the
  /// accelerations at t, then the body moved by the exact exponential of that twist over Δt.
  /// A body turning about a fixed axis has a constant twist direction, so it stays on its
  /// circle up to rounding.
  ScrewEuler,
  /// ScrewEuler followed by the projection of projectOntoConstraints(): for chains of
  /// rotating frames (Fig. 6.3), where the screw update alone still drifts.
  ScrewEulerProjected,
};

/// "forward_euler", "semi_implicit_euler", "rk4_constant_forces", "rk4_resolved_forces",
/// "screw_euler" or "screw_euler_projected".
std::string stickingMethodName(StickingMethod method);

/// The names of the methods.
inline constexpr EnumNames<StickingMethod, 6> kStickingMethodNames{{
    {StickingMethod::ForwardEuler, "forward_euler"},
    {StickingMethod::SemiImplicitEuler, "semi_implicit_euler"},
    {StickingMethod::RungeKutta4ConstantForces, "rk4_constant_forces"},
    {StickingMethod::RungeKutta4ResolvedForces, "rk4_resolved_forces"},
    {StickingMethod::ScrewEuler, "screw_euler"},
    {StickingMethod::ScrewEulerProjected, "screw_euler_projected"},
}};
/// Parses the names of stickingMethodName(); throws std::invalid_argument on an unknown name,
/// listing the valid ones.
StickingMethod parseStickingMethod(const std::string& name);
/// Every method, in the order of the enum.
std::vector<StickingMethod> allStickingMethods();

/// Tolerances of the post-step projection (post-stabilisation: M. B. Cline and D. K. Pai,
/// "Post-Stabilization for Rigid Body Simulation with Contact and Constraints", ICRA 2003).
struct ProjectionParams {
  /// Stop once every point pair is this close, m. 1e-9 m is a millionth of the boxes' size and
  /// a thousand times the rounding of positions of order 1 m.
  double positionTolerance = 1e-9;
  /// At most this many Gauss–Newton iterations; each one typically squares the error.
  int maxIterations = 10;
};

/// What one projection did.
struct ProjectionReport {
  int iterations = 0;           ///< Gauss–Newton iterations taken
  double errorBefore = 0.0;     ///< max over points of |p_b − p_a| before, m
  double errorAfter = 0.0;      ///< the same after, m
};

/// Moves the bodies of `scene` back onto its point constraints and removes the velocity
/// components that violate them.
///
/// Positions: Gauss–Newton on C(x, q) = p_b − p_a = 0 in the mass metric: the correction
/// δ = −W Jᵀ (J W Jᵀ)⁺ C (W = M⁻¹, the pseudo-inverse by complete orthogonal decomposition),
/// applied as x += δx, q ← exp(δθ) q, until max |C_i| <= params.positionTolerance or
/// params.maxIterations. Velocities: w ← w − W Jᵀ (J W Jᵀ)⁺ J w, the mass-weighted nearest
/// velocity with no relative velocity at any point.
/// \throws std::invalid_argument as solveStickingForces for bad points, and for a
///         non-positive tolerance or iteration count.
ProjectionReport projectOntoConstraints(StickingScene& scene, const ProjectionParams& params = {});

/// Advances every movable body of `scene` by dt (s, > 0) with `method`, the sticking forces
/// solved at the start of the step (and, for RungeKutta4ResolvedForces, at every stage).
/// Returns the solution at the start of the step (its normal forces are those of time t).
/// \throws std::invalid_argument for dt <= 0 or not finite.
StickingSolution stepSticking(StickingScene& scene, StickingMethod method, double dt,
                              const ProjectionParams& projection = {});

}  // namespace boxsim
