/// \file
/// The Jacobian of a set of sticking point constraints (\thesis{§6.2}): how the relative
/// velocity of every pair of coinciding material points depends on the bodies' velocities. The
/// sticking force solve and the post-step projection share it.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "boxsim/exterior_rotation/sticking_scene.hpp"

namespace boxsim {

/// J, M⁻¹ and the velocity-product terms of point constraints at the world's current state.
///
/// Generalized velocities are w = (v₀, ω₀, v₁, ω₁, …) over the movable bodies (six columns
/// each, in body order; immovable bodies have none). Row block i of J maps w to the relative
/// velocity of point i, ṗ_b − ṗ_a = (v_b + ω_b × r_b) − (v_a + ω_a × r_a), r = R r_local:
/// the block of b is [I, −[r_b]×], that of a its negative. It keeps references to the world and
/// the points it was built from, which must outlive it and not change while it is used.
class ConstraintJacobian {
 public:
  /// Builds J for `points` in `world` (derived quantities up to date).
  /// \throws std::invalid_argument for a point whose body indices are out of range or equal,
  ///         or whose b is immovable.
  ConstraintJacobian(const World& world, const std::vector<PointConstraint>& points);

  /// The number of generalized velocities, 6 × (movable bodies).
  int columns() const { return columns_; }
  /// The first column of body k, or −1 for an immovable body.
  int column(int k) const { return column_[k]; }
  /// W Jᵀ, W = M⁻¹ = diag(m⁻¹ I, I⁻¹(world)) per body: (6n × 3m).
  Eigen::MatrixXd inverseMassTimesTransposed() const;
  /// c: per point, ω_b × (ω_b × r_b) − ω_a × (ω_a × r_a), m/s^2 (3m).
  Eigen::VectorXd velocityProducts() const;
  /// C: per point, p_b − p_a, m (3m): zero when every pair of material points coincides.
  Eigen::VectorXd positionError() const;
  /// The bodies' generalized velocity w (6n), m/s and rad/s.
  Eigen::VectorXd velocities() const;

  Eigen::MatrixXd J;  ///< 3m × 6n, unitless (translation) and m (rotation) entries

 private:
  const World& world_;
  const std::vector<PointConstraint>& points_;
  std::vector<int> column_;
  int columns_ = 0;
  std::vector<Vec3> rA_, rB_;  // the points' offsets from a's and b's centres, world, m
};

}  // namespace boxsim
