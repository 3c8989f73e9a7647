// Worlds the verification tests start from.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>

#include "boxsim/collision/contact.hpp"
#include "boxsim/core/math.hpp"
#include "boxsim/core/world.hpp"

namespace boxsim::testing {

/// An empty world without gravity or ground, with restitution e: bodies in free space.
inline World spaceWorld(double restitution = 0.9) {
  World world;
  world.gravity = Vec3::Zero();
  world.restitution = restitution;
  return world;
}

/// An empty world with the usual ground: its top face at y = 0, 100 m square.
inline World groundWorld() {
  World world;
  world.addGround(0.0, 50.0);
  return world;
}

/// The heap of Fig. 6.7 read with the origin on the ground (clump100_ground.json), measured
/// against a cone of the cubes' volume V and height H: base radius R = √(3V / πH), its mass at
/// an rms distance √0.3 R from its axis (∫r³(1 − r/R)dr over ∫r(1 − r/R)dr).
struct HeapMeasure {
  double rmsRadius = 0.0;  ///< m, rms horizontal distance of the movable bodies from the y axis
  double top = 0.0;        ///< m, the highest centre
  int beyondCone = 0;      ///< movable bodies farther from the axis than the cone's base radius
  int count = 0;           ///< movable bodies
  double coneRadius = 0.0;     ///< m, R
  double coneRmsRadius = 0.0;  ///< m, √0.3 R
};

/// The heap measure of `world`'s movable bodies against the cone of `volume` m³, `height` m.
inline HeapMeasure measureHeap(const World& world, double volume, double height) {
  HeapMeasure m;
  m.coneRadius = std::sqrt(3.0 * volume / (kPi * height));
  m.coneRmsRadius = std::sqrt(0.3) * m.coneRadius;
  double sumSquares = 0.0;
  for (const RigidBody& b : world.bodies) {
    if (b.immovable) continue;
    const double r2 = b.s.x.x() * b.s.x.x() + b.s.x.z() * b.s.x.z();
    sumSquares += r2;
    ++m.count;
    if (r2 > m.coneRadius * m.coneRadius) ++m.beyondCone;
    m.top = std::max(m.top, b.s.x.y());
  }
  if (m.count > 0) m.rmsRadius = std::sqrt(sumSquares / m.count);
  return m;
}

/// Whether two separating-axis results are the same bit for bit, every field.
inline bool sameResult(const SeparatingAxisResult& x, const SeparatingAxisResult& y) {
  return sameBits(x.depth, y.depth) && sameBits(x.normal, y.normal) && x.kind == y.kind &&
         x.indexA == y.indexA && x.indexB == y.indexB && x.intersecting == y.intersecting;
}

}  // namespace boxsim::testing
