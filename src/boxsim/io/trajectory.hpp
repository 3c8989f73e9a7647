/// \file
/// Recorded trajectories in memory and as gnuplot `.dat` files.
///
/// File format (plain text, one frame per row, whitespace separated):
/// \code
/// # boxsim trajectory 1
/// # scene: chapters/basic_colliding/scenes/die.json
/// # method: basic_colliding
/// # dt: 0.016666666666666666
/// # seed: 0
/// # body 0 ground half_extents 50 0.5 50 immovable 1
/// # body 1 die half_extents 0.5 0.5 0.5 immovable 0
/// # columns: t kinetic potential total contacts events bisections b0_x b0_y b0_z b0_qw b0_qx b0_qy b0_qz b1_x ...
/// 0 0 4.905 4.905 0 0 0 0 -0.5 0 1 0 0 0 0 1 0 ...
/// \endcode
/// Every `# key: value` line is a parameter of the run. The `# body` lines give each body's
/// name, half extents (m) and whether it is immovable. Columns: time (s), kinetic, potential
/// and total energy (J), contact count, collision events and bisection steps in the frame,
/// then position (m) and unit quaternion (w, x, y, z) of every body, immovable ones included.
#pragma once

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "boxsim/core/frame_sink.hpp"

namespace boxsim {

/// A trajectory file that does not follow the format above. what() reads "FILE:LINE: problem".
class TrajectoryFormatError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Formats a trajectory in the file format above (full double precision, round-trippable):
/// formatTrajectoryHeader() followed by appendTrajectoryRow() for every frame.
/// Throws std::invalid_argument when a body name is empty or holds white space.
std::string formatTrajectory(const Trajectory& trajectory);

/// The header of the file format above for a run with parameters `meta` and bodies `bodies`:
/// every line up to and including the `# columns:` line.
/// Throws std::invalid_argument when a body name is empty or holds white space.
std::string formatTrajectoryHeader(const std::map<std::string, std::string>& meta,
                                   const std::vector<TrajectoryBody>& bodies);

/// Appends the row of one frame (its newline included) to `out`.
void appendTrajectoryRow(std::string& out, const TrajectoryFrame& frame);

/// Writes formatTrajectory() to path, whole or not at all (temporary file, then rename).
/// Throws std::runtime_error naming the path when it cannot.
void writeTrajectory(const std::string& path, const Trajectory& trajectory);

/// Reads a trajectory file whole (readTrajectory() into a TrajectoryCollector).
/// Throws TrajectoryFormatError naming the file and line on a malformed file (missing header,
/// wrong column count, non-numeric field, a header line after the first frame), and
/// std::runtime_error when the file cannot be opened.
Trajectory readTrajectory(const std::string& path);

/// Reads a trajectory file frame by frame into `sink`, holding one frame at a time:
/// FrameSink::begin() with the header lines when the first frame (or the end of the file) is
/// reached, FrameSink::push() for every frame, FrameSink::finish() at the end.
/// Throws as readTrajectory(const std::string&) does, and whatever the sink throws.
void readTrajectory(const std::string& path, FrameSink& sink);

}  // namespace boxsim
