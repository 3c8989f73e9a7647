#include "boxsim/io/trajectory_file_writer.hpp"

#include "boxsim/io/trajectory.hpp"

namespace boxsim {

namespace {
/// Rows are handed to the file in pieces of about this many bytes.
constexpr std::size_t kBufferBytes = 64 * 1024;
}  // namespace

void TrajectoryFileWriter::begin(const std::map<std::string, std::string>& meta,
                                 const std::vector<TrajectoryBody>& bodies) {
  buffer_ = formatTrajectoryHeader(meta, bodies);
  buffer_.reserve(2 * kBufferBytes);
}

void TrajectoryFileWriter::push(const TrajectoryFrame& frame) {
  appendTrajectoryRow(buffer_, frame);
  if (buffer_.size() < kBufferBytes) return;
  file_.write(buffer_);
  buffer_.clear();
}

void TrajectoryFileWriter::finish() {
  file_.write(buffer_);
  buffer_.clear();
  file_.commit();
}

}  // namespace boxsim
