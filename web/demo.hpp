/// \file
/// The interactive demo of web/: one of the thesis' scenes under one technique, stepped a
/// frame at a time, with boxes shot from the eye point as in \thesis{Fig. 6.6} ("a box is shot
/// out from the eye point towards the pyramid"), the display filters of \thesis{§5.5}, and a
/// digest of every body state for the check that the WebAssembly build steps the same bits as
/// the native one. Compiled to WebAssembly for the page (bindings.cpp) and natively for that
/// check (digest_main.cpp).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/core/stepper.hpp"
#include "boxsim/core/world.hpp"
#include "boxsim/filtering/box_filter.hpp"
#include "boxsim/filtering/envelope_filter.hpp"
#include "boxsim/io/recorder.hpp"

namespace boxsim::web {

/// What the page can choose.
struct DemoSettings {
  /// "pyramid" (Fig. 6.6, a base of 10 cubes), "clump" (Fig. 6.7, 100 cubes), "die" (§4.2),
  /// "tower" (10 cubes), "clump_ground" (clump100_ground.json: Fig. 6.7 thrown at the ground),
  /// "pile" (pile343.json: 343 tumbling cubes settling into a heap) or "clump1000" (Fig. 6.7
  /// with 1000 cubes): the shipped scenes of chapters/impulse_damped/scenes, built alike.
  std::string scene = "pyramid";
  /// "damped", "impulse", "analytic" or "basic_colliding" (techniques.hpp).
  std::string method = "damped";
  bool sleep = true;               ///< computational stability, §4.5 (damped only)
  bool geometricStability = true;  ///< §5.4 (damped only)
  /// Display filter: "none", "box" (causal, H = 2: the display lags 2 frames) or "envelope".
  std::string filter = "none";
  /// Coulomb friction μ (static and dynamic) of every body, the ground and the shots
  /// included, >= 0; 0 is the thesis' frictionless contact (§3.3.2).
  double friction = 0.0;
};

/// Per-body flags of flags().
enum BodyFlag : std::uint8_t {
  kImmovable = 1,            ///< the ground, and shots not yet fired
  kAsleep = 2,               ///< computational stability (§4.5)
  kGeometricallyStable = 4,  ///< SETGEOMETRICALLYSTABLE (§5.4): drawn dark, as in Fig. 5.6
};

/// A scene running under a technique. Steps are 1/60 s. Its Recorder hands every frame to the
/// demo itself, a FrameSink, which passes it through the display filter into poses().
class Demo : public FrameSink {
 public:
  /// Shots the page may fire before it must restart the scene.
  static constexpr int kShots = 12;
  /// Speed of a shot, m/s, as the shot of the pyramid scene (pyramid10_shot.json).
  static constexpr double kShotSpeed = 20.0;

  /// Builds the scene and the stepper. Throws std::invalid_argument naming an unknown scene,
  /// method or filter, or a setting the method does not take.
  explicit Demo(const DemoSettings& settings);

  /// One step of 1/60 s; returns the collision events it resolved.
  int step();
  /// Fires the next shot: a unit cube of 1 kg from `from` (m) along `direction` (normalised
  /// here) at kShotSpeed, entering at the next step. Returns false when all kShots are spent.
  bool shoot(const Vec3& from, const Vec3& direction);
  /// Shots the page may still fire in this run.
  int shotsLeft() const { return kShots - shotsFired_; }

  double time() const { return time_; }  ///< s
  int bodyCount() const { return static_cast<int>(world_.bodies.size()); }
  const World& world() const { return world_; }
  /// Half extents of every body, 3 a body, m.
  std::vector<double> halfExtents() const;
  /// The displayed pose of every body after the display filter: x, y, z (m), then the
  /// quaternion's x, y, z, w; 7 a body.
  const std::vector<double>& poses() const { return poses_; }
  /// BodyFlag bits, one a body.
  std::vector<std::uint8_t> flags() const;
  /// How far the farthest movable body is from where it started, m (shots not counted).
  double largestDisplacement() const;
  /// FrameSink: starts the display filter for the recorded bodies (the shots, immovable
  /// until fired, pass it unfiltered).
  void begin(const std::map<std::string, std::string>& meta,
             const std::vector<TrajectoryBody>& bodies) override;
  /// FrameSink: the frame through the display filter into poses().
  void push(const TrajectoryFrame& frame) override;
  /// FrameSink: nothing to finish.
  void finish() override {}

  /// The scene as other engines build it (web/peer_engines.js): per body, 17 numbers, half
  /// extents (m, 3), position (m, 3), orientation quaternion x, y, z, w (4), velocity (m/s, 3),
  /// angular velocity (rad/s, 3) and mass (kg; 0 for an immovable body: the ground, and the
  /// shots until fired, which wait far from the scene). The shots are bodies kShots last.
  std::vector<double> sceneBodies() const;
  /// The world's coefficient of restitution (unitless), every contact's.
  double restitution() const { return world_.restitution; }
  /// m/s²: the world's gravity, y up.
  double gravity() const { return world_.gravity.norm(); }
  /// The deepest overlap of any two bodies (boxsim's separating-axis test, ground included),
  /// m: deepestPenetration of this run's world.
  double penetration() const { return deepestPenetration(world_); }
  /// The same measure at poses of another engine: `poses` as poses() gives them (7 a body, for
  /// the bodies of this scene in order); this run's state is left alone. Throws
  /// std::invalid_argument when the count is not 7 a body.
  double penetrationAt(const std::vector<double>& poses) const;

  /// FNV-1a hash (64 bit, as 16 hex digits) of the bytes of every double of every body's
  /// state x, q, P, L: equal digests mean, all but certainly, the same bits.
  std::string stateDigest() const;

 private:
  DemoSettings settings_;
  World world_;
  std::unique_ptr<Stepper> stepper_;
  std::unique_ptr<Recorder> recorder_;  ///< frames of the world, to push()
  std::unique_ptr<CausalBoxFilter> boxFilter_;
  std::unique_ptr<CausalEnvelopeFilter> envelopeFilter_;
  std::vector<Vec3> start_;  ///< every body's position at the start
  int firstShot_ = 0;        ///< index of the first shot's body
  int shotsFired_ = 0;
  long steps_ = 0;
  double time_ = 0.0;
  std::vector<double> poses_;


};

}  // namespace boxsim::web
