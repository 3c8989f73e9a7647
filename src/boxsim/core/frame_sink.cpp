#include "boxsim/core/frame_sink.hpp"

namespace boxsim {

void TrajectoryCollector::begin(const std::map<std::string, std::string>& meta,
                                const std::vector<TrajectoryBody>& bodies) {
  trajectory_.meta = meta;
  trajectory_.bodies = bodies;
  trajectory_.frames.clear();
}

void replayTrajectory(const Trajectory& trajectory, FrameSink& sink) {
  sink.begin(trajectory.meta, trajectory.bodies);
  for (const TrajectoryFrame& frame : trajectory.frames) sink.push(frame);
  sink.finish();
}

}  // namespace boxsim
