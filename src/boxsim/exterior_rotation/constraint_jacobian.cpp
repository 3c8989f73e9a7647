#include "boxsim/exterior_rotation/constraint_jacobian.hpp"

#include <stdexcept>
#include <string>

namespace boxsim {

ConstraintJacobian::ConstraintJacobian(const World& world, const std::vector<PointConstraint>& points)
    : world_(world), points_(points) {
  const int bodyCount = static_cast<int>(world.bodies.size());
  column_.assign(bodyCount, -1);
  for (int k = 0; k < bodyCount; ++k)
    if (!world.bodies[k].immovable) {
      column_[k] = columns_;
      columns_ += 6;
    }
  const int m = static_cast<int>(points.size());
  J = Eigen::MatrixXd::Zero(3 * m, columns_);
  for (int i = 0; i < m; ++i) {
    const PointConstraint& p = points[i];
    if (p.a < 0 || p.a >= bodyCount || p.b < 0 || p.b >= bodyCount || p.a == p.b)
      throw std::invalid_argument("sticking point " + std::to_string(i) + " joins bodies " +
                                  std::to_string(p.a) + " and " + std::to_string(p.b) +
                                  "; give two different bodies of the " +
                                  std::to_string(bodyCount) + " in the world");
    if (world.bodies[p.b].immovable)
      throw std::invalid_argument("sticking point " + std::to_string(i) + ": body b (" +
                                  world.names[p.b] + ") is immovable; make the movable one b");
    rA_.push_back(world.bodies[p.a].R * p.rA);
    rB_.push_back(world.bodies[p.b].R * p.rB);
    const int cb = column_[p.b];
    J.block<3, 3>(3 * i, cb) = Mat3::Identity();
    J.block<3, 3>(3 * i, cb + 3) = -crossMatrix(rB_.back());
    const int ca = column_[p.a];
    if (ca >= 0) {
      J.block<3, 3>(3 * i, ca) = -Mat3::Identity();
      J.block<3, 3>(3 * i, ca + 3) = crossMatrix(rA_.back());
    }
  }
}

Eigen::MatrixXd ConstraintJacobian::inverseMassTimesTransposed() const {
  Eigen::MatrixXd WJt = J.transpose();
  for (std::size_t k = 0; k < world_.bodies.size(); ++k) {
    const int c = column_[k];
    if (c < 0) continue;
    const RigidBody& body = world_.bodies[k];
    WJt.middleRows<3>(c) *= body.invMass;
    WJt.middleRows<3>(c + 3) = (body.Iinv * WJt.middleRows<3>(c + 3)).eval();
  }
  return WJt;
}

Eigen::VectorXd ConstraintJacobian::velocityProducts() const {
  Eigen::VectorXd c(3 * points_.size());
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const Vec3& wa = world_.bodies[points_[i].a].omega;
    const Vec3& wb = world_.bodies[points_[i].b].omega;
    c.segment<3>(3 * i) = wb.cross(wb.cross(rB_[i])) - wa.cross(wa.cross(rA_[i]));
  }
  return c;
}

Eigen::VectorXd ConstraintJacobian::positionError() const {
  Eigen::VectorXd C(3 * points_.size());
  for (std::size_t i = 0; i < points_.size(); ++i)
    C.segment<3>(3 * i) = (world_.bodies[points_[i].b].s.x + rB_[i]) -
                          (world_.bodies[points_[i].a].s.x + rA_[i]);
  return C;
}

Eigen::VectorXd ConstraintJacobian::velocities() const {
  Eigen::VectorXd w(columns_);
  for (std::size_t k = 0; k < world_.bodies.size(); ++k) {
    const int c = column_[k];
    if (c < 0) continue;
    w.segment<3>(c) = world_.bodies[k].v;
    w.segment<3>(c + 3) = world_.bodies[k].omega;
  }
  return w;
}

}  // namespace boxsim
