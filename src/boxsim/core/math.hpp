/// \file
/// Vector, matrix and quaternion aliases over Eigen, and the physical constants every
/// technique shares. SI units throughout (m, kg, s, rad); y is up.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace boxsim {

using Vec3 = Eigen::Vector3d;     ///< A 3-vector in m, m/s, N, ... as the context says.
using Mat3 = Eigen::Matrix3d;     ///< A 3x3 matrix (rotation, inertia tensor).
using Quat = Eigen::Quaterniond;  ///< A unit quaternion for orientation (w, x, y, z).

/// Standard gravity (0, -9.81, 0) m/s^2, along -y as the thesis assumes (\thesis{§5.4}).
inline Vec3 standardGravity() { return Vec3(0.0, -9.81, 0.0); }

/// The skew-symmetric cross-product matrix: `skew(a) * b == a.cross(b)`.
inline Mat3 skew(const Vec3& a) {
  Mat3 s;
  s << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  return s;
}

}  // namespace boxsim
