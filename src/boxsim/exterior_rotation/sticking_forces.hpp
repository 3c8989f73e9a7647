/// \file
/// Contact forces for contacts that stick (\thesis{§6.2}; the analytic method of \thesis{§2.6},
/// \thesis{§3.3.1}): with infinite static friction every contact point is a bilateral point
/// constraint, and the forces are those that make the relative acceleration of every pair of
/// coinciding material points zero at this instant. This is Baraff's acceleration-level
/// formulation (D. Baraff, "Fast Contact Force Computation for Nonpenetrating Rigid Bodies",
/// SIGGRAPH 1994, §3–§5; equality constraints as in "Linear-Time Dynamics using Lagrange
/// Multipliers", SIGGRAPH 1996, §3) with every contact active and no sign condition, so the
/// LCP becomes a linear system.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "boxsim/core/integrator.hpp"
#include "boxsim/exterior_rotation/sticking_scene.hpp"

namespace boxsim {

/// The instantaneous solution of the sticking contact problem.
struct StickingSolution {
  /// Per body: the sum of the contact forces on it (N, through the centre of mass) and their
  /// torque about the centre of mass (N m); gravity is not included. Zero for immovable bodies.
  std::vector<Wrench> wrench;
  std::vector<Vec3> a;      ///< per body: linear acceleration of the centre, m/s^2
  std::vector<Vec3> alpha;  ///< per body: angular acceleration, rad/s^2
  /// Three entries per PointConstraint: the force on body b at its point (N, world), −that on
  /// a. The minimum-norm choice among the equivalent ones when the points are redundant.
  Eigen::VectorXd lambda;
  /// Per StickingContact: the total force of its points on body b, N (world). Unique even
  /// when the points are redundant: internal stresses cancel in the sum.
  std::vector<Vec3> contactForce;
  /// max over points of |relative acceleration| after the solve, m/s^2 (rounding only).
  double residual = 0.0;
  int rank = 0;  ///< the numerical rank of the contact matrix J M⁻¹ Jᵀ
};

/// The load on one contact: its normal force and the friction coefficient sticking needs.
struct ContactLoad {
  double normal = 0.0;      ///< N; > 0 compressive, < 0 the contact would have to pull
  double tangential = 0.0;  ///< |friction force|, N
  /// |f_t| / f_n: the static friction coefficient sticking needs; +inf when f_n <= 0.
  double requiredMu = 0.0;
};

/// Solves for the sticking contact forces of `points` in `world` at the current state.
///
/// Each point i asks that p̈_b − p̈_a = 0, where a material point at r from a body's centre
/// accelerates as a + α × r + ω × (ω × r) and α = I⁻¹(τ − ω × L) (the velocity-product terms,
/// centripetal and gyroscopic, included). With J (3m × 6n) the point Jacobian, W = M⁻¹ and
/// ẇ_free the accelerations under gravity alone, the forces solve
/// (J W Jᵀ) λ = −(J ẇ_free + c), c the centripetal terms. Face contacts (four corners) and edge
/// contacts (two ends) make J W Jᵀ singular; Eigen's CompleteOrthogonalDecomposition gives the
/// minimum-norm λ, and the accelerations it implies are unique.
/// \param world  bodies with derived quantities up to date (RigidBody::updateDerived)
/// \param points the constraints; each b must be movable
/// \param contactCount the number of contacts the points refer to (contactForce's size)
/// \throws std::invalid_argument for a point whose bodies are out of range, equal, or whose b is
///         immovable, or whose contact index is outside [0, contactCount).
StickingSolution solveStickingForces(const World& world, const std::vector<PointConstraint>& points,
                                     int contactCount);

/// The normal and tangential force of contact `contact` of `scene` in `solution`, the normal
/// taken from the contact's first point (its normalLocal turned into the world).
/// \throws std::invalid_argument when the contact has no point.
ContactLoad contactLoad(const StickingScene& scene, const StickingSolution& solution, int contact);

}  // namespace boxsim
