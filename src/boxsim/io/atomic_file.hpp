/// \file
/// Output files are written whole or not at all: into a temporary file beside the target,
/// then renamed over it, so a crash or an error never leaves a partial file behind.
#pragma once

#include <cstdio>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

namespace boxsim {

/// An output file that cannot be created: its folder is missing or not writable, or the path
/// names a folder or something else than a regular file (a device, a pipe). The sysexits name
/// of this failure is EX_CANTCREAT.
class CannotCreateError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// An output file that could not be written whole: a write, the flush or the final rename
/// failed (a full disk, an I/O error; EX_IOERR). The temporary file is removed.
class WriteError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Writes `content` to `path` atomically (an AtomicFileWriter written at once).
/// Throws CannotCreateError or WriteError naming the path and the system error when it cannot;
/// no temporary file is left behind.
void writeFileAtomically(const std::string& path, const std::string& content);

/// Creates a new, empty, uniquely named file in `directory`, named `stem` followed by the process
/// id and a counter, with the permissions
/// of any new file (0666 less the umask) and returns its path. Throws CannotCreateError naming
/// the directory when it cannot.
std::string makeTemporaryIn(const std::string& directory, const std::string& stem);

/// makeTemporaryIn() in the directory of `path` (so that a rename onto `path` is atomic), with
/// the stem made of a dot, the file name and `.tmp`. Throws CannotCreateError naming `path`
/// when the temporary file cannot be made, and when `path` exists and is not a regular file
/// (a folder; a device such as /dev/null, which the final rename would replace).
std::string makeTemporaryBeside(const std::string& path);

/// Renames `temporaryPath` over `path`; throws WriteError (and removes the temporary
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

/// An output file written piece by piece: into a temporary file beside its target from the
/// start, renamed over the target by commit(). Until then the target is untouched; destroyed
/// without a commit (an error, an exception) the writer removes its temporary file. Memory use
/// does not grow with the amount written.
class AtomicFileWriter {
 public:
  /// Creates the temporary file beside `path` (makeTemporaryBeside()) and opens it, so that a
  /// path that cannot be written fails here, before any work.
  /// \throws CannotCreateError naming the path.
  explicit AtomicFileWriter(std::string path);
  AtomicFileWriter(const AtomicFileWriter&) = delete;
  AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;
  ~AtomicFileWriter();
  /// Appends `data`. \throws WriteError naming the path and the system error.
  void write(std::string_view data);
  /// Flushes, syncs and closes the temporary file and renames it over the target.
  /// \throws WriteError naming the path and the system error (the temporary file is removed).
  void commit();
  /// The target path.
  const std::string& path() const { return path_; }
  /// The temporary file's path, empty once committed.
  const std::string& temporaryPath() const { return temporary_.path(); }

 private:
  std::string path_;
  TemporaryFile temporary_;
  std::FILE* file_ = nullptr;
};

}  // namespace boxsim
