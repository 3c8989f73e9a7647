/// \file
/// Output files are written whole or not at all: into a temporary file beside the target,
/// then renamed over it, so a crash or an error never leaves a partial file behind.
#pragma once

#include <string>

namespace boxsim {

/// Writes `content` to `path` atomically (temporary file in the same directory, then rename).
/// Throws std::runtime_error naming the path and the system error when it cannot; no
/// temporary file is left behind.
void writeFileAtomically(const std::string& path, const std::string& content);

/// Creates a new, empty, uniquely named file in `directory`, named `stem` followed by the process
/// id and a counter, with the permissions
/// of any new file (0666 less the umask) and returns its path. Throws std::runtime_error naming
/// the directory when it cannot.
std::string makeTemporaryIn(const std::string& directory, const std::string& stem);

/// makeTemporaryIn() in the directory of `path` (so that a rename onto `path` is atomic), with
/// the stem made of a dot, the file name and `.tmp`.
std::string makeTemporaryBeside(const std::string& path);

/// Renames `temporaryPath` over `path`; throws std::runtime_error (and removes the temporary
/// file) when it cannot.
void commitTemporary(const std::string& temporaryPath, const std::string& path);

/// Owns a temporary file and removes it when it goes out of scope, unless released (after a
/// successful commitTemporary()).
class TemporaryFile {
 public:
  /// Takes ownership of the file at `path`.
  explicit TemporaryFile(std::string path) : path_(std::move(path)) {}
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;
  ~TemporaryFile();
  /// The file's path.
  const std::string& path() const { return path_; }
  /// Gives up ownership: the file is no longer removed.
  void release() { path_.clear(); }

 private:
  std::string path_;
};

}  // namespace boxsim
