/// \file
/// The removal of a run's temporary file when the process is interrupted: a long run streams
/// its trajectory into a temporary file, and Ctrl-C must not leave it behind.
#pragma once

#include <string>

namespace boxsim::cli {

/// While it lives, SIGINT, SIGTERM and SIGHUP (Ctrl-C during a long run, a closed terminal)
/// first remove the temporary file at `path`, then end the process as the signal would have.
/// A signal ignored when it is armed stays ignored (nohup, a background job). One at a time;
/// the previous handlers come back when it is destroyed.
class RemoveOnSignal {
 public:
  /// Arms the handlers for `path` (a path longer than PATH_MAX is not armed).
  explicit RemoveOnSignal(const std::string& path);
  RemoveOnSignal(const RemoveOnSignal&) = delete;
  RemoveOnSignal& operator=(const RemoveOnSignal&) = delete;
  ~RemoveOnSignal();
};

}  // namespace boxsim::cli
