/// \file
/// The exact motion of a §6.2 scene in reduced coordinates (\thesis{§6.2}): the sticking group
/// is a planar chain of rigid links, each turning about a hinge parallel to z, one hinge angle
/// per link. Figs. 6.1 and 6.2 are one link about the table's edge (a compound pendulum);
/// Fig. 6.3 is two (a compound double pendulum). The equations are integrated with GSL's
/// Prince–Dormand 8(9) method (gsl_odeiv2_step_rk8pd) at tight tolerance.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "boxsim/exterior_rotation/sticking_scene.hpp"

namespace boxsim {

/// Tolerances of the reference integration.
struct HingeReferenceParams {
  /// Absolute error per step of GSL's step control, rad and rad/s. 1e-12 keeps the reference
  /// ten orders of magnitude below the errors it measures (mm and above over 1 m of travel).
  double absoluteTolerance = 1e-12;
  double relativeTolerance = 1e-12;  ///< relative error per step of GSL's step control
};

/// The reduced model of a StickingScene, integrated forward in time.
///
/// Link k has mass m_k, moment of inertia I_k about its centre of mass (about z), the vector c_k
/// from its hinge to its centre and, for k < n − 1, h_k from its hinge to the next hinge (both
/// at t = 0, turned by R(φ_k) later). With u_kj = R(φ_j) h_j for j < k and R(φ_k) c_k for j = k,
/// Kane's equations give M(φ) φ̈ = f(φ, φ̇) with
/// M_ij = Σ_{k ≥ i,j} m_k u_ki · u_kj + δ_ij I_i and
/// f_i = Σ_{k ≥ i} m_k (Σ_{j ≤ k} φ̇_j² u_ki × u_kj + u_ki × g) (planar cross products);
/// for one link this is I_O φ̈ = (c × m g)_z, the compound pendulum.
class HingeReference {
 public:
  /// The model of `scene`'s links at t = 0, at rest (every scene starts at rest).
  /// \throws std::invalid_argument for a scene without links, a link without bodies, or a link
  ///         body that is already moving (start the scene at rest).
  explicit HingeReference(const StickingScene& scene, const HingeReferenceParams& params = {});
  ~HingeReference();
  HingeReference(const HingeReference&) = delete;             ///< owns a GSL driver
  HingeReference& operator=(const HingeReference&) = delete;  ///< owns a GSL driver

  /// Integrates on to time t (s, not before the current time).
  /// \throws std::invalid_argument for a t before the current time; std::runtime_error when
  ///         GSL reports a failure.
  void advanceTo(double t);

  double time() const { return t_; }  ///< the current time, s
  /// The hinge angles φ_k, rad about +z, relative to the scene's initial pose (each link's
  /// absolute turn, not relative to the link before).
  Eigen::VectorXd angles() const;
  Eigen::VectorXd angularVelocities() const;  ///< φ̇_k, rad/s
  /// φ̈_k at the current state, rad/s^2.
  Eigen::VectorXd angularAccelerations() const;
  /// Kinetic plus gravitational potential energy, J (potential zero at y = 0).
  double energy() const;
  /// The world position of hinge k now, m.
  Vec3 hinge(int k) const;
  /// Sets the poses and velocities of every link body of `world` (the scene's world or a copy)
  /// to the reference's now.
  void applyTo(World& world) const;
  /// The centre of body `body` now, m. \throws std::invalid_argument for a body in no link.
  Vec3 centre(int body) const;

 private:
  struct Link {
    std::vector<int> bodies;
    double mass = 0.0, inertia = 0.0;
    Eigen::Vector2d c, h;
  };
  static int rate(double t, const double* y, double* dydt, void* self);
  Eigen::VectorXd acceleration(const double* y) const;
  int linkOf(int body) const;

  std::vector<Link> links_;
  std::vector<Vec3> hinge0_;          // hinges at t = 0
  std::vector<Vec3> x0_;              // every body's centre at t = 0
  std::vector<Quat> q0_;              // every body's orientation at t = 0
  std::vector<double> mass_;          // every body's mass (0 for bodies in no link)
  Vec3 gravity_;
  std::vector<double> y_;             // φ then φ̇
  double t_ = 0.0;
  struct Driver;
  std::unique_ptr<Driver> driver_;
};

}  // namespace boxsim
