/// \file
/// Vector, matrix and quaternion aliases over Eigen, and the physical constants every
/// technique shares. SI units throughout (m, kg, s, rad); y is up.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <cstring>
#include <string>

namespace boxsim {

using Vec3 = Eigen::Vector3d;     ///< A 3-vector in m, m/s, N, ... as the context says.
using Mat3 = Eigen::Matrix3d;     ///< A 3x3 matrix (rotation, inertia tensor).
using Quat = Eigen::Quaterniond;  ///< A unit quaternion for orientation (w, x, y, z).

/// Standard gravity (0, -9.81, 0) m/s^2, along -y as the thesis assumes (\thesis{§5.4}).
inline Vec3 standardGravity() { return Vec3(0.0, -9.81, 0.0); }

/// π, for conversions between degrees (scene files) and radians.
inline constexpr double kPi = 3.14159265358979323846;

/// The rotation by `angleDeg` degrees about `axis` (any non-zero length; normalised here).
inline Quat axisAngleDegrees(const Vec3& axis, double angleDeg) {
  return Quat(Eigen::AngleAxisd(angleDeg * kPi / 180.0, axis.normalized()));
}

/// The shortest decimal text that reads back to exactly `value` (round trip), for output
/// headers and data files: 1e-05, 0.9, 0.016666666666666666.
std::string shortestText(double value);

/// Appends shortestText(value) to `out` without a string of its own: a trajectory row writes
/// thousands of numbers, and a text of more than 15 characters would cost an allocation each.
void appendShortestText(std::string& out, double value);

/// Whether two numbers are the same double bit for bit (so -0 differs from 0, and a NaN equals
/// itself): the test for reusing a value computed from them. Compared as 64-bit words, which
/// the compiler keeps inline (a memcmp of a matrix was a library call in the hot loops); copied
/// with memcpy, not std::bit_cast, which the WebAssembly build's C++ library lacks.
inline bool sameBits(double a, double b) {
  std::uint64_t x = 0, y = 0;
  std::memcpy(&x, &a, sizeof(double));
  std::memcpy(&y, &b, sizeof(double));
  return x == y;
}
/// sameBits for vectors, component by component.
inline bool sameBits(const Vec3& a, const Vec3& b) {
  return sameBits(a.x(), b.x()) && sameBits(a.y(), b.y()) && sameBits(a.z(), b.z());
}
/// sameBits for 3×3 matrices, coefficient by coefficient.
inline bool sameBits(const Mat3& a, const Mat3& b) {
  for (int k = 0; k < 9; ++k)
    if (!sameBits(a.data()[k], b.data()[k])) return false;
  return true;
}

/// [r]×, the matrix of the cross product: crossMatrix(r) v = r × v.
inline Eigen::Matrix3d crossMatrix(const Eigen::Vector3d& r) {
  Eigen::Matrix3d m;
  m << 0.0, -r.z(), r.y(), r.z(), 0.0, -r.x(), -r.y(), r.x(), 0.0;
  return m;
}

/// The first `count` (at most 4) points of q, m, about a point inside their convex hull, in
/// counter-clockwise order of their angle about it: the outline of a contact patch.
std::array<int, 4> counterClockwiseOrder(const std::array<Eigen::Vector2d, 4>& q, int count);

}  // namespace boxsim
