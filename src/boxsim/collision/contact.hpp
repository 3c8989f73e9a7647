/// \file
/// Results of the narrow phase: the separating-axis test and the contact manifold of two
/// oriented boxes (\thesis{§3.2}; D. Eberly, "Dynamic Collision Detection using Oriented
/// Bounding Boxes", and "Intersection of Convex Objects: The Method of Separating Axes").
#pragma once

#include <array>
#include <cstdint>

#include "boxsim/collision/obb.hpp"

namespace boxsim {

/// Which kind of axis the separating-axis test found to be the axis of least penetration.
enum class AxisKind : std::uint8_t {
  FaceA,     ///< a face normal of box A (axis index in indexA)
  FaceB,     ///< a face normal of box B (axis index in indexB)
  EdgeEdge,  ///< the cross product of edge direction indexA of A and indexB of B
};

/// Outcome of the 15-axis separating-axis test of two OBBs.
struct SeparatingAxisResult {
  /// True when the boxes overlap with depth > 0 along every one of the 15 axes.
  bool intersecting = false;
  /// Overlap along the chosen axis, m. Positive: penetration depth. Zero or negative: the
  /// boxes are separated (or touching) and -depth is the largest gap found along a tested axis
  /// (a lower bound of their distance).
  double depth = 0.0;
  /// Unit axis pointing from box A towards box B.
  Vec3 normal = Vec3::UnitY();
  AxisKind kind = AxisKind::FaceA;  ///< which kind of axis was chosen
  int indexA = 0;  ///< face axis of A, or edge direction of A, 0..2
  int indexB = 0;  ///< face axis of B, or edge direction of B, 0..2
};

/// One point of a contact manifold.
struct ContactPoint {
  Vec3 position = Vec3::Zero();  ///< world, m: midway between the two surfaces
  double depth = 0.0;            ///< penetration along the manifold normal, m (> 0 overlapping)
  /// Identifies the pair of features that made the point (stable while the features stay the
  /// same), so a point can be matched across steps.
  std::uint32_t featureId = 0;
};

/// The contact manifold of two boxes: a shared normal and up to four points.
struct ContactManifold {
  int a = -1;                      ///< index of body A in the world (-1 when unused)
  int b = -1;                      ///< index of body B
  Vec3 normal = Vec3::UnitY();     ///< unit, from A towards B
  AxisKind kind = AxisKind::FaceA; ///< face contact (FaceA, FaceB) or edge-edge contact
  /// Deepest penetration of the points, m; the separating-axis depth when count == 0.
  double depth = 0.0;
  std::array<ContactPoint, 4> points{};  ///< the first `count` are valid
  int count = 0;                   ///< number of valid points, 0..4

  /// The mean of the contact points, m: the single contact point of a collision (\alg{COLLIDE L7}).
  Vec3 centroid() const {
    Vec3 c = Vec3::Zero();
    for (int i = 0; i < count; ++i) c += points[i].position;
    return count > 0 ? Vec3(c / count) : c;
  }
};

}  // namespace boxsim
