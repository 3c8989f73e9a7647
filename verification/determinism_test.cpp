// Determinism (DESIGN.md): the same scene and parameters give a bit-identical trajectory. Every
// technique runs the same many-contact scene twice in one process, and every double of every
// body's state (x, q, P, L) is compared bit for bit after every step. Across builds (Release
// against Debug), cmake/compare_builds.sh compares the trajectory files of the shipped scenes.
#include <catch2/catch.hpp>

#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "boxsim/io/scene_builders.hpp"
#include "boxsim/techniques.hpp"
#include "test_worlds.hpp"

using namespace boxsim;

namespace {

/// A pyramid of base 3 (6 unit cubes, every one touching its neighbours and the ground) and a
/// die dropped spinning onto its apex: resting contacts, a collision and sliding in one scene.
World manyContacts() {
  World world = testing::groundWorld();
  PyramidSpec pyramid;
  pyramid.base = 3;
  addPyramid(world, pyramid);
  DieSpec die;
  die.position = Vec3(0.2, 6.0, 0.1);
  die.angularVelocity = Vec3(1.0, 2.0, -0.5);
  addDie(world, die);
  return world;
}

/// Every double of every body's state after each step, in order.
std::vector<double> trajectory(const std::string& method, int steps) {
  World world = manyContacts();
  const std::unique_ptr<Stepper> stepper = makeStepper(method);
  std::vector<double> out;
  for (int k = 0; k < steps; ++k) {
    stepper->step(world, 1.0 / 60.0);
    for (const RigidBody& b : world.bodies) {
      out.insert(out.end(), b.s.x.data(), b.s.x.data() + 3);
      out.insert(out.end(), b.s.q.coeffs().data(), b.s.q.coeffs().data() + 4);
      out.insert(out.end(), b.s.P.data(), b.s.P.data() + 3);
      out.insert(out.end(), b.s.L.data(), b.s.L.data() + 3);
    }
  }
  return out;
}

}  // namespace

TEST_CASE("Every technique gives a bit-identical trajectory when run twice on a scene of many "
          "contacts",
          "[techniques][determinism]") {
  for (const std::string& method : methodNames()) {
    // 1 s; the chronological techniques meet their event limits on the resting pyramid every
    // step, so they run a tenth of it, and the swept timewarp, whose conservative advancement
    // makes each of its 1000 events a frame dear (2.5 s a frame here), one frame.
    const bool chronological = method != "impulse" && method != "damped";
    const int steps = method == "timewarp_swept" ? 1 : chronological ? 6 : 60;
    const std::vector<double> first = trajectory(method, steps);
    const std::vector<double> second = trajectory(method, steps);
    INFO(method);
    REQUIRE(first.size() == second.size());
    REQUIRE(!first.empty());
    // memcmp, not ==: -0.0 against 0.0 and NaN against NaN count as different bits.
    CHECK(std::memcmp(first.data(), second.data(), first.size() * sizeof(double)) == 0);
  }
}
