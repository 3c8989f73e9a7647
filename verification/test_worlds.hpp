// Worlds the verification tests start from.
#pragma once

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

}  // namespace boxsim::testing
