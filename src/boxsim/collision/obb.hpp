/// \file
/// Oriented bounding boxes: the only shape the thesis simulates (\thesis{§3.1}).
#pragma once

#include <array>

#include "boxsim/core/rigid_body.hpp"

namespace boxsim {

/// An oriented box in world space: centre, axes (columns of a rotation matrix) and half
/// extents along those axes.
struct Obb {
  Vec3 center = Vec3::Zero();          ///< m
  Mat3 axes = Mat3::Identity();        ///< column k is the box's k-th unit axis in world space
  Vec3 halfExtents = Vec3::Constant(0.5);  ///< m, all > 0

  /// The box of a rigid body at its current state (uses the derived R).
  static Obb of(const RigidBody& body) { return Obb{body.s.x, body.R, body.halfExtents}; }

  /// Corner k (0..7) in world space. Bit 0, 1, 2 of k choose the sign along axis 0, 1, 2
  /// (bit set: +, clear: -).
  Vec3 corner(int k) const {
    Vec3 c = center;
    for (int i = 0; i < 3; ++i)
      c += ((k >> i) & 1 ? 1.0 : -1.0) * halfExtents[i] * axes.col(i);
    return c;
  }
};

}  // namespace boxsim
