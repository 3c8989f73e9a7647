// The impact page's measurement (measureImpact, peer_impact.hpp) on a scripted engine whose
// impact is known: a projectile falls freely until a given step, which stops it and sets two
// boxes of the target moving, one of them below the threshold.
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "peer_impact.hpp"

namespace {

using boxsim::Launch;
using boxsim::Vec3;
using boxsim::World;
using boxsim::peers::ImpactMeasures;
using boxsim::peers::kImpactSpeed;
using boxsim::peers::PeerEngine;
using boxsim::peers::PeerPose;
using boxsim::peers::PeerScene;
using boxsim::peers::SceneSpec;

constexpr double kDt = 1.0 / 60.0;
constexpr long kImpactStep = 20;  ///< the step (1-based) the script's impact happens in
constexpr double kStruck = 5.0;   ///< m/s, the struck box's speed after it
constexpr double kNudged = 0.6;   ///< m/s, a neighbour's: above the threshold
constexpr double kGrazed = 0.1;  ///< m/s, another's: below the threshold

/// Ground, three boxes of the target (indices 1-3) and the projectile (4), launched at 0.1 s.
World target() {
  World world;
  world.addGround();
  for (int i = 0; i < 3; ++i)
    boxsim::addBox(world, "box" + std::to_string(i), Vec3::Constant(0.5),
                   Vec3(1.1 * i, 0.5, 0.0));
  const int projectile =
      boxsim::addBox(world, "projectile", Vec3::Constant(0.5), Vec3(0.0, 3.0, 10.0));
  world.bodies[static_cast<std::size_t>(projectile)].immovable = true;
  Launch launch;
  launch.body = projectile;
  launch.time = 0.1;
  launch.velocity = Vec3(0.0, 0.0, -20.0);
  world.launches.push_back(launch);
  return world;
}

/// Moves the boxes by the script: the projectile in free flight from its launch to the impact,
/// then at 2 m/s; in the impact's step box 1 takes kStruck, box 2 kNudged, box 3 kGrazed.
class ScriptedEngine : public PeerEngine {
 public:
  std::string name() const override { return "scripted"; }
  std::string settings() const override { return "none"; }
  void load(const PeerScene& scene) override {
    scene_ = scene;
    poses_.assign(scene.boxes.size(), PeerPose{});
    for (std::size_t i = 0; i < poses_.size(); ++i) poses_[i].x = scene.boxes[i].x;
    steps_ = 0;
  }
  void step(double dt, double t) override {
    ++steps_;
    PeerPose& shot = poses_[4];
    if (t + 1e-9 * dt >= scene_.boxes[4].launchTime && !launched_) {
      shot.v = scene_.boxes[4].v;
      launched_ = true;
    }
    if (launched_) shot.v += dt * scene_.gravity;
    if (steps_ == kImpactStep) {
      shot.v = Vec3(0.0, 0.0, -2.0);
      poses_[1].v = Vec3(0.0, 0.0, -kStruck);
      poses_[2].v = Vec3(0.0, 0.0, -kNudged);
      poses_[3].v = Vec3(0.0, 0.0, -kGrazed);
    }
    for (PeerPose& p : poses_) p.x += dt * p.v;
  }
  void read(std::vector<PeerPose>& poses) const override { poses = poses_; }
  int asleep() const override { return 0; }

 private:
  PeerScene scene_;
  std::vector<PeerPose> poses_;
  long steps_ = 0;
  bool launched_ = false;
};

SceneSpec spec(std::function<World()> build) {
  SceneSpec s;
  s.base = "scripted";
  s.duration = 1.0;
  s.build = std::move(build);
  s.launches = true;
  return s;
}

}  // namespace

TEST_CASE("The impact page finds the step that stops the projectile, the box it struck and the "
          "boxes it set moving",
          "[peers][impact]") {
  ScriptedEngine engine;
  const ImpactMeasures m = boxsim::peers::measureImpact(spec(target), engine, kDt);
  REQUIRE(m.found);
  CHECK(m.time == Approx(kImpactStep * kDt));
  CHECK(m.struckBody == 1);
  CHECK(m.struckSpeed == Approx(kStruck));
  CHECK(m.struckSpeedLater == Approx(kStruck));  // the script leaves it at that speed
  CHECK(m.moving == 2);                            // the grazed box is below the threshold
  // In flight since 0.1 s (the launch's step): 20 m/s across, falling by g t.
  const double fall = 9.81 * (kImpactStep - 1 - 6) * kDt;
  CHECK(m.projectileBefore == Approx(std::hypot(20.0, fall)).epsilon(1e-3));
  CHECK(m.projectileAfter == Approx(2.0));
  CHECK(m.delivered == Approx(kStruck + kNudged + kGrazed));  // 1 kg boxes, all along -z
  // From the impact's step to the end (41 steps) box 1 travels 3.4 m, box 2 0.41 m, box 3
  // 0.07 m: the first two are beyond kMovedDistance (0.1 m).
  CHECK(m.movedAtEnd == 2);
}

TEST_CASE("The impact page refuses a scene that launches no box", "[peers][impact]") {
  ScriptedEngine engine;
  const auto still = [] {
    World world = target();
    world.launches.clear();
    return world;
  };
  CHECK_THROWS_WITH(boxsim::peers::measureImpact(spec(still), engine, kDt),
                    Catch::Contains("no launched box"));
}
