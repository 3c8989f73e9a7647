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

namespace boxsim {

namespace {
std::runtime_error ioError(const std::string& what, const std::string& path) {
  return std::runtime_error(what + " '" + path + "': " + std::strerror(errno));
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
  throw ioError("cannot create a temporary file in", dir.string());
}

std::string makeTemporaryBeside(const std::string& path) {
  const std::filesystem::path target(path);
  try {
    // Appended piece by piece: GCC 12 at -O3 warns falsely (-Wstringop-overflow or
    // -Warray-bounds) on "." + name + ".tmp" inlined here.
    std::string name = ".";
    name += target.filename().string();
    name += ".tmp";
    return makeTemporaryIn(target.parent_path().string(), name);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("cannot write '" + path + "': " + e.what());
  }
}

void commitTemporary(const std::string& temporaryPath, const std::string& path) {
  if (std::rename(temporaryPath.c_str(), path.c_str()) != 0) {
    const std::runtime_error error = ioError("cannot write", path);
    std::remove(temporaryPath.c_str());
    throw error;
  }
}

void writeFileAtomically(const std::string& path, const std::string& content) {
  TemporaryFile temporary(makeTemporaryBeside(path));
  std::FILE* file = std::fopen(temporary.path().c_str(), "wb");
  bool ok = file != nullptr;
  if (ok) ok = std::fwrite(content.data(), 1, content.size(), file) == content.size();
  if (file != nullptr) ok = (std::fflush(file) == 0) && ok && (::fsync(fileno(file)) == 0);
  if (file != nullptr) ok = (std::fclose(file) == 0) && ok;
  if (!ok) throw ioError("cannot write", path);
  commitTemporary(temporary.path(), path);
  temporary.release();
}

}  // namespace boxsim
