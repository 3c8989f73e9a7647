/// \file
/// Where recorded frames go, one at a time and in time order: a trajectory file
/// (TrajectoryFileWriter), memory (TrajectoryCollector), or a filter of \thesis{§5.5} in front
/// of either. A run streamed through sinks holds one frame plus what its filters need, however
/// many steps it takes.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "boxsim/io/trajectory.hpp"

namespace boxsim {

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
