/// \file
/// The recorder keeps one frame per step: every body's pose, the energies, and the counts of
/// contacts, collision events and bisection steps (the data flow of DESIGN.md).
#pragma once

#include <string>

#include "boxsim/core/stepper.hpp"
#include "boxsim/io/trajectory.hpp"

namespace boxsim {

/// Records frames of a world into a Trajectory.
class Recorder {
 public:
  /// Starts a recording of `world`'s bodies (names, extents) with run parameters `meta`
  /// (written as `# key: value` header lines; include the seed).
  Recorder(const World& world, std::map<std::string, std::string> meta);

  /// Appends a frame at time t (s) with the stats of the step that led to it.
  void capture(const World& world, double t, const StepStats& stats = {});

  /// The frames recorded so far.
  const Trajectory& trajectory() const { return trajectory_; }
  /// Writes the recording to path, whole or not at all.
  void write(const std::string& path) const { writeTrajectory(path, trajectory_); }

 private:
  Trajectory trajectory_;
};

}  // namespace boxsim
