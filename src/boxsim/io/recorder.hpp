/// \file
/// The recorder keeps one frame per step: every body's pose, the energies, and the counts of
/// contacts, collision events and bisection steps (the data flow of DESIGN.md). It keeps the
/// frames in memory, or passes each one on to a FrameSink and keeps none.
#pragma once

#include <map>
#include <string>

#include "boxsim/core/stepper.hpp"
#include "boxsim/core/frame_sink.hpp"
#include "boxsim/io/trajectory.hpp"

namespace boxsim {

/// Records frames of a world into a Trajectory, or into a FrameSink.
class Recorder {
 public:
  /// Starts a recording of `world`'s bodies (names, extents) with run parameters `meta`
  /// (written as `# key: value` header lines; include the seed), kept in memory.
  Recorder(const World& world, std::map<std::string, std::string> meta);

  /// Starts a recording that passes every frame to `sink` and keeps none: calls
  /// sink.begin() with `meta` and the bodies now. The caller calls sink.finish() after the
  /// last frame; `sink` must outlive the recorder.
  Recorder(const World& world, std::map<std::string, std::string> meta, FrameSink& sink);

  /// Appends a frame at time t (s) with the stats of the step that led to it.
  void capture(const World& world, double t, const StepStats& stats = {});

  /// True when the frames are kept in memory (no sink).
  bool keepsFrames() const { return sink_ == nullptr; }
  /// The header and the frames recorded so far (no frames when they go to a sink).
  const Trajectory& trajectory() const { return trajectory_; }
  /// Writes the recording to path, whole or not at all.
  void write(const std::string& path) const { writeTrajectory(path, trajectory_); }

 private:
  Trajectory trajectory_;
  FrameSink* sink_ = nullptr;
};

}  // namespace boxsim
