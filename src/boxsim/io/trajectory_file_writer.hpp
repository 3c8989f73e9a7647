/// \file
/// A trajectory file written as the run goes: the frame sink at the end of `boxsim run`.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "boxsim/io/atomic_file.hpp"
#include "boxsim/core/frame_sink.hpp"

namespace boxsim {

/// Writes a trajectory file (the format of trajectory.hpp) frame by frame into a temporary
/// file beside its target, and renames it over the target in finish(): the file is written
/// whole or not at all, as writeTrajectory() writes it, byte for byte. It holds one buffer of
/// rows (about 64 KiB), however many frames pass.
class TrajectoryFileWriter final : public FrameSink {
 public:
  /// Creates the temporary file beside `path` now, so that an output path that cannot be
  /// written fails before a run starts. \throws CannotCreateError naming the path.
  explicit TrajectoryFileWriter(std::string path) : file_(std::move(path)) {}
  /// Writes the header. \throws std::invalid_argument for a bad body name
  /// (formatTrajectoryHeader()), WriteError when the write fails.
  void begin(const std::map<std::string, std::string>& meta,
             const std::vector<TrajectoryBody>& bodies) override;
  /// Writes the frame's row. \throws WriteError when the write fails.
  void push(const TrajectoryFrame& frame) override;
  /// Writes what is buffered and renames the file over its target. \throws WriteError.
  void finish() override;
  /// The target path.
  const std::string& path() const { return file_.path(); }
  /// The temporary file's path (empty once finished), for removal on a signal.
  const std::string& temporaryPath() const { return file_.temporaryPath(); }

 private:
  AtomicFileWriter file_;
  std::string buffer_;
};

}  // namespace boxsim
