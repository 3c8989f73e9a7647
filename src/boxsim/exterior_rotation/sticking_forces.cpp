#include "boxsim/exterior_rotation/sticking_forces.hpp"

#include <Eigen/QR>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "boxsim/exterior_rotation/constraint_jacobian.hpp"

namespace boxsim {

StickingSolution solveStickingForces(const World& world, const std::vector<PointConstraint>& points,
                                     int contactCount) {
  for (std::size_t i = 0; i < points.size(); ++i)
    if (points[i].contact < 0 || points[i].contact >= contactCount)
      throw std::invalid_argument("sticking point " + std::to_string(i) + " names contact " +
                                  std::to_string(points[i].contact) + "; there are " +
                                  std::to_string(contactCount) + " contacts");
  const ConstraintJacobian jac(world, points);
  const int n = jac.columns();

  // The generalized accelerations under gravity and the gyroscopic term alone (ẇ_free).
  Eigen::VectorXd wFree = Eigen::VectorXd::Zero(n);
  for (std::size_t k = 0; k < world.bodies.size(); ++k) {
    const int c = jac.column(static_cast<int>(k));
    if (c < 0) continue;
    const RigidBody& body = world.bodies[k];
    wFree.segment<3>(c) = world.gravity;
    wFree.segment<3>(c + 3) = body.Iinv * (-body.omega.cross(body.s.L));
  }
  // Baraff 1994 §5: A = J M⁻¹ Jᵀ, b = J ẇ_free + c; A λ = −b.
  // DEVIATION(§3.3.1): every point is an equality, so there is no pivoting, no ε and no clamp
  // of negative forces; a contact may pull. contactLoad() reports it, and each scene's window
  // ends before any hinge would.
  const Eigen::MatrixXd WJt = jac.inverseMassTimesTransposed();
  const Eigen::MatrixXd A = jac.J * WJt;
  const Eigen::VectorXd b = jac.J * wFree + jac.velocityProducts();
  const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(A);

  StickingSolution s;
  s.lambda = cod.solve(-b);
  s.rank = static_cast<int>(cod.rank());
  const Eigen::VectorXd accel = wFree + WJt * s.lambda;
  const Eigen::VectorXd generalizedForce = jac.J.transpose() * s.lambda;
  const Eigen::VectorXd relative = jac.J * accel + jac.velocityProducts();
  for (int i = 0; i < relative.size() / 3; ++i)
    s.residual = std::max(s.residual, relative.segment<3>(3 * i).norm());

  const std::size_t bodyCount = world.bodies.size();
  s.wrench.assign(bodyCount, Wrench{});
  s.a.assign(bodyCount, Vec3::Zero());
  s.alpha.assign(bodyCount, Vec3::Zero());
  for (std::size_t k = 0; k < bodyCount; ++k) {
    const int c = jac.column(static_cast<int>(k));
    if (c < 0) continue;
    s.wrench[k].force = generalizedForce.segment<3>(c);
    s.wrench[k].torque = generalizedForce.segment<3>(c + 3);
    s.a[k] = accel.segment<3>(c);
    s.alpha[k] = accel.segment<3>(c + 3);
  }
  s.contactForce.assign(contactCount, Vec3::Zero());
  for (std::size_t i = 0; i < points.size(); ++i)
    s.contactForce[points[i].contact] += s.lambda.segment<3>(3 * static_cast<int>(i));
  return s;
}

ContactLoad contactLoad(const StickingScene& scene, const StickingSolution& solution, int contact) {
  for (const PointConstraint& p : scene.points) {
    if (p.contact != contact) continue;
    const Vec3 n = scene.world.bodies[p.normalBody].R * p.normalLocal;
    const Vec3& f = solution.contactForce[contact];
    ContactLoad load;
    load.normal = f.dot(n);
    load.tangential = (f - load.normal * n).norm();
    load.requiredMu = load.normal > 0.0 ? load.tangential / load.normal
                                        : std::numeric_limits<double>::infinity();
    return load;
  }
  throw std::invalid_argument("contact " + std::to_string(contact) + " of scene '" + scene.name +
                              "' has no sticking point");
}

}  // namespace boxsim
