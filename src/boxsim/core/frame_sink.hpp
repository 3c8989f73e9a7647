/// \file
/// Recorded trajectories in memory (the file format is io/trajectory.hpp's), and where recorded
/// frames go, one at a time and in time order: a trajectory file
/// (TrajectoryFileWriter), memory (TrajectoryCollector), or a filter of \thesis{§5.5} in front
/// of either. A run streamed through sinks holds one frame plus what its filters need, however
/// many steps it takes.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "boxsim/core/math.hpp"

namespace boxsim {

/// A body as a trajectory describes it.
struct TrajectoryBody {
  std::string name;  ///< unique, no white space
  Vec3 halfExtents = Vec3::Constant(0.5);  ///< m
  bool immovable = false;  ///< drawn as scenery, never moves
};

/// One recorded frame.
struct TrajectoryFrame {
  double t = 0.0;          ///< s
  double kinetic = 0.0;    ///< J
  double potential = 0.0;  ///< J
  int contacts = 0;        ///< contact manifolds (touching pairs) at the end of the frame
  int events = 0;          ///< collision events during the frame (StepStats::events)
  int bisections = 0;      ///< bisection steps (roll-backs) during the frame
  std::vector<Vec3> x;     ///< position of each body, m
  std::vector<Quat> q;     ///< orientation of each body
};

/// A whole recorded run.
struct Trajectory {
  /// Run parameters, written as `# key: value` header lines (scene, method, dt, seed, ...),
  /// in key order.
  std::map<std::string, std::string> meta;
  std::vector<TrajectoryBody> bodies;   ///< in body order, immovable ones included
  std::vector<TrajectoryFrame> frames;  ///< in time order
};

/// A consumer of a trajectory, header first, then frame by frame.
class FrameSink {
 public:
  virtual ~FrameSink() = default;
  /// Called once, before any frame: the run's parameters (the `# key: value` header lines)
  /// and its bodies.
  virtual void begin(const std::map<std::string, std::string>& meta,
                     const std::vector<TrajectoryBody>& bodies) = 0;
  /// One frame, with one pose per body given to begin(); frames come in time order.
  virtual void push(const TrajectoryFrame& frame) = 0;
  /// Called once after the last frame; a sink that writes a file commits it here.
  virtual void finish() = 0;
};

/// A sink that keeps the whole trajectory in memory.
class TrajectoryCollector final : public FrameSink {
 public:
  void begin(const std::map<std::string, std::string>& meta,
             const std::vector<TrajectoryBody>& bodies) override;
  void push(const TrajectoryFrame& frame) override { trajectory_.frames.push_back(frame); }
  void finish() override {}
  /// What was collected so far.
  const Trajectory& trajectory() const { return trajectory_; }
  /// Moves the collected trajectory out, leaving the collector empty.
  Trajectory take() { return std::move(trajectory_); }

 private:
  Trajectory trajectory_;
};

/// Sends a trajectory held in memory through `sink`: begin(), push() for every frame, finish().
void replayTrajectory(const Trajectory& trajectory, FrameSink& sink);

}  // namespace boxsim
