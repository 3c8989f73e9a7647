/// \file
/// Whole-or-nothing output files.
#include "boxsim/io/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <utility>

namespace boxsim {

namespace {
std::string systemError(const std::string& what, const std::string& path) {
  return what + " '" + path + "': " + std::strerror(errno);
}

/// Refuses a target in a folder that does not exist, and a target that exists and is not a
/// regular file: the rename would replace a folder's name or a device node (as root,
/// /dev/null itself) with the temporary file.
void requireCreatableTarget(const std::filesystem::path& target) {
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(target, error);
  const std::filesystem::path folder = target.parent_path().empty() ? "." : target.parent_path();
  if (!std::filesystem::is_directory(folder, error))
    throw CannotCreateError("cannot create '" + target.string() + "': there is no folder '" +
                            folder.string() + "'; create it or give a path in an existing folder");
  if (!std::filesystem::exists(status) || std::filesystem::is_regular_file(status)) return;
  if (std::filesystem::is_directory(status))
    throw CannotCreateError("cannot create '" + target.string() +
                            "': it is a folder; give the path of a file in it");
  throw CannotCreateError("cannot create '" + target.string() +
                          "': it is not a regular file (a device, pipe or socket); output is "
                          "written into a temporary file and renamed over the target, so give "
                          "the path of a regular file");
}
}  // namespace

TemporaryFile::~TemporaryFile() {
  if (!path_.empty()) std::remove(path_.c_str());
}

std::string makeTemporaryIn(const std::string& directory, const std::string& stem) {
  static std::atomic<unsigned> counter{0};
  const std::filesystem::path dir(directory.empty() ? std::string(".") : directory);
  for (int attempt = 0; attempt < 100; ++attempt) {
    const std::string candidate =
        (dir / (stem + std::to_string(::getpid()) + "-" + std::to_string(counter++))).string();
    // O_EXCL makes the name ours alone; mode 0666 lets the umask decide the permissions, as for
    // any other new file.
    const int fd = ::open(candidate.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) {
      ::close(fd);
      return candidate;
    }
    if (errno != EEXIST) break;
  }
  throw CannotCreateError(systemError("cannot create a temporary file in", dir.string()));
}

std::string makeTemporaryBeside(const std::string& path) {
  const std::filesystem::path target(path);
  requireCreatableTarget(target);
  try {
    // Appended piece by piece: GCC 12 at -O3 warns falsely (-Wstringop-overflow or
    // -Warray-bounds) on "." + name + ".tmp" inlined here.
    std::string name = ".";
    name += target.filename().string();
    name += ".tmp";
    return makeTemporaryIn(target.parent_path().string(), name);
  } catch (const CannotCreateError& e) {
    throw CannotCreateError("cannot create '" + path + "': " + e.what());
  }
}

void commitTemporary(const std::string& temporaryPath, const std::string& path) {
  if (std::rename(temporaryPath.c_str(), path.c_str()) != 0) {
    const WriteError error(systemError("cannot write", path));
    std::remove(temporaryPath.c_str());
    throw error;
  }
}

AtomicFileWriter::AtomicFileWriter(std::string path)
    : path_(std::move(path)), temporary_(makeTemporaryBeside(path_)) {
  file_ = std::fopen(temporary_.path().c_str(), "wb");
  if (file_ == nullptr)
    throw CannotCreateError(systemError("cannot create", path_));
}

AtomicFileWriter::~AtomicFileWriter() {
  if (file_ != nullptr) std::fclose(file_);
}

void AtomicFileWriter::write(std::string_view data) {
  if (file_ == nullptr) throw WriteError("cannot write '" + path_ + "': already committed");
  if (std::fwrite(data.data(), 1, data.size(), file_) != data.size())
    throw WriteError(systemError("cannot write", path_));
}

void AtomicFileWriter::commit() {
  if (file_ == nullptr) throw WriteError("cannot write '" + path_ + "': already committed");
  int error = 0;
  if (std::fflush(file_) != 0 || ::fsync(fileno(file_)) != 0) error = errno;
  if (std::fclose(file_) != 0 && error == 0) error = errno;
  file_ = nullptr;
  if (error != 0) {
    errno = error;
    throw WriteError(systemError("cannot write", path_));
  }
  commitTemporary(temporary_.path(), path_);
  temporary_.release();
}

void writeFileAtomically(const std::string& path, const std::string& content) {
  AtomicFileWriter writer(path);
  writer.write(content);
  writer.commit();
}

}  // namespace boxsim
