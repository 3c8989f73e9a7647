/// \file
/// Running one scene under one engine, and what the comparison reports of it: the time of
/// every step (over repetitions) and the physics, measured with one yardstick for every
/// engine (boxsim's separating-axis test on the engine's poses).
#pragma once

#include <functional>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "boxsim/core/world.hpp"
#include "peer_engine.hpp"

namespace boxsim::peers {

/// A scene of the comparison: a base scene under one restitution and one sleep setting.
struct SceneSpec {
  std::string base;       ///< the scene's name without its settings, e.g. "clump1000"
  double duration = 5.0;  ///< simulated time, s
  std::function<World()> build;
  double restitution = 0.9;  ///< Newtonian coefficient for every engine
  bool sleep = true;         ///< every engine's sleeping of bodies at rest
  double friction = 0.5;     ///< Coulomb coefficient for the engines that have friction
  bool tower = false;        ///< report the top box's drift
  bool die = false;          ///< report the die's horizontal travel
  bool launches = false;     ///< a box is launched (the shot pyramids): Bullet's CCD row too
  bool userFile = false;     ///< read from a user's scene file (--scene-file), not the page's own

  /// "clump1000 e=0", with ", sleep off" when the engines do not sleep.
  std::string label() const;
};

/// The physics of one run, the same for every repetition of a deterministic engine.
struct RunMeasures {
  int bodies = 0;                 ///< movable boxes
  double meanPenetration = 0;     ///< m, the deepest penetration of a measured frame, averaged
  double finalPenetration = 0;    ///< m, the deepest penetration after the last step
  double maxPenetration = 0;      ///< m, the deepest penetration of any measured frame
  double finalKinetic = 0;        ///< J, translational and rotational, after the last step
  int asleepAtEnd = 0;            ///< movable boxes the engine holds asleep after the last step
  double allAsleepFrom = -1;      ///< s, from when every movable box stays asleep; -1: never
  double allAtRestFrom = -1;      ///< s, from when every box stays below kRestSpeed/kRestSpin
  double drift = -1;              ///< m: tower top drift, die horizontal travel; -1: none
};

/// One engine on one scene: step times over every repetition and the first one's measures.
struct RunResult {
  std::string engine;
  std::vector<double> stepMs;     ///< every step of every repetition, ms
  std::vector<double> repMeanMs;  ///< the mean step of each repetition, ms
  RunMeasures measures;
  /// KiB: the peak resident set of a fresh process that ran the scene once under this engine
  /// alone (peakResidentKiB); -1: not measured.
  long peakRssKiB = -1;
  long startRssKiB = -1;  ///< the same process with the scene built and no engine stepped
  /// The first repetition's step time by stage (PeerEngine::stages), s, largest first; empty
  /// for engines that do not report stages.
  std::vector<std::pair<std::string, double>> stages;
  double stagedStepsMs = 0.0;  ///< ms, the first repetition's step times summed
  std::optional<StepWork> work;  ///< the first repetition's work (PeerEngine::work)
  /// boxsim damped on the scenes of the aims: its shared work, from a run of its own
  /// (PeerEngine::sharedWork).
  std::optional<SharedWork> sharedWork;
  /// The same measured in a run of its own on two threads (the "+threads2" engine), to set
  /// the model's loops beside what they took on this machine.
  std::optional<SharedWork> sharedWorkTwoThreads;

  double meanMs() const;    ///< over every step of every repetition
  double medianMs() const;  ///< over every step of every repetition
  double p95Ms() const;     ///< 95th percentile over every step of every repetition
};

/// A box counts as at rest below these (a 1 kg unit cube: 5e-5 J of translation).
constexpr double kRestSpeed = 0.01;  ///< m/s
constexpr double kRestSpin = 0.02;   ///< rad/s

/// A user's scene file (docs/scene_format.md) as a scene of the comparison, named by its file's
/// stem, run for `seconds` (> 0) at the file's own restitution and sleeping on. Its bodies'
/// friction is left out: as in the page's own scenes, boxsim's rows are frictionless (the
/// thesis) unless an engine asks for '+friction', which, like the peers, gives every body the
/// comparison's coefficient (SceneSpec::friction). The file is read now, so that a bad one
/// fails before anything is timed: throws boxsim::SceneError naming the file, the place and the
/// fix, as `boxsim run` reports it.
SceneSpec sceneFromFile(const std::string& path, double seconds);

/// The scene `spec` describes, as every engine loads it (its restitution, sleeping, friction).
PeerScene peerSceneOf(const SceneSpec& spec);

/// Runs `spec` once under `engine` (a fresh engine per run) with steps of dt seconds; appends
/// its step times to `result` and, on the first repetition, measures the physics.
void runRepetition(const SceneSpec& spec, PeerEngine& engine, double dt, RunResult& result);

/// Runs `spec` once under `engine` (nullptr: builds the scene and steps nothing), without
/// timing or measuring: the work of a memory run (measurePeakMemory).
void runOnce(const SceneSpec& spec, PeerEngine* engine, double dt);

/// KiB: this process' peak resident set so far (VmHWM of /proc/self/status), or -1 where
/// there is no such file.
long peakResidentKiB();

/// The peak resident set, KiB, of a fresh run of this program with `arguments` (after the
/// program's name, which is read from /proc/self/exe), as that run reports it on its standard
/// output (the last number it prints); -1 where it cannot be started or reports nothing.
long peakResidentOfRun(const std::vector<std::string>& arguments);
/// The standard output of `program` run with `arguments` (each quoted for the shell), or
/// nullopt where it cannot be started or exits with an error. An empty `program` is this
/// program itself (read from /proc/self/exe).
std::optional<std::string> outputOfRun(const std::string& program,
                                       const std::vector<std::string>& arguments);
/// A digest (64-bit FNV-1a) of the bits of every pose, position and orientation: equal for two
/// runs that ended bit for bit alike.
std::uint64_t poseDigest(const std::vector<PeerPose>& poses);

}  // namespace boxsim::peers
