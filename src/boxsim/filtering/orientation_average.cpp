#include "boxsim/filtering/orientation_average.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <stdexcept>

namespace boxsim {

std::string orientationAverageName(OrientationAverage average) {
  return enumName(kOrientationAverageNames, average);
}

OrientationAverage parseOrientationAverage(const std::string& name) {
  return parseEnum(kOrientationAverageNames, name, "orientation average");
}

Quat averageOrientations(const Quat* q, std::size_t n, const Quat& reference,
                         OrientationAverage method) {
  if (n == 0) throw std::invalid_argument("averageOrientations needs at least one quaternion");
  const Eigen::Vector4d ref = reference.coeffs();
  // One sample is its own average: returned as it is (up to the sign), not renormalised, so a
  // window of one frame leaves the pose bit for bit unchanged.
  if (n == 1) return q[0].coeffs().dot(ref) < 0.0 ? Quat(-q[0].w(), -q[0].x(), -q[0].y(), -q[0].z()) : q[0];
  Eigen::Vector4d mean;
  if (method == OrientationAverage::SignAlignedMean) {
    // The sum has a component ≥ 1 along the reference (every term ≥ 0 along it, the centre
    // sample 1), so it never vanishes and its normalisation is safe.
    Eigen::Vector4d sum = Eigen::Vector4d::Zero();
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Vector4d c = q[i].coeffs();
      sum += c.dot(ref) < 0.0 ? Eigen::Vector4d(-c) : c;
    }
    mean = sum / static_cast<double>(n);
  } else {
    // Markley et al. 2007, eq. 13: M = Σ q qᵀ; the average is M's principal eigenvector.
    Eigen::Matrix4d M = Eigen::Matrix4d::Zero();
    for (std::size_t i = 0; i < n; ++i) M += q[i].coeffs() * q[i].coeffs().transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> solver(M);
    mean = solver.eigenvectors().col(3);  // eigenvalues come in increasing order
    if (mean.dot(ref) < 0.0) mean = -mean;
  }
  mean.normalize();
  return Quat(mean[3], mean[0], mean[1], mean[2]);  // coeffs() order is x, y, z, w
}

double rotationAngle(const Quat& a, const Quat& b) {
  const Quat d = a.conjugate() * b;
  return 2.0 * std::atan2(d.vec().norm(), std::abs(d.w()));
}

Vec3 rotationVector(const Quat& a, const Quat& b) {
  const Quat d = b * a.conjugate();
  const double s = d.vec().norm();
  if (s == 0.0) return Vec3::Zero();
  // The shorter of the two rotations: flip the axis with the sign of w.
  const double angle = 2.0 * std::atan2(s, std::abs(d.w()));
  const Vec3 axis = (d.w() < 0.0 ? -1.0 : 1.0) * d.vec() / s;
  return angle * axis;
}

}  // namespace boxsim
