#include "boxsim/io/atomic_file.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <vector>

namespace boxsim {

namespace {
std::runtime_error ioError(const std::string& what, const std::string& path) {
  return std::runtime_error(what + " '" + path + "': " + std::strerror(errno));
}
}  // namespace

std::string makeTemporaryBeside(const std::string& path) {
  const std::filesystem::path target(path);
  std::filesystem::path dir = target.parent_path();
  if (dir.empty()) dir = ".";
  std::string pattern = (dir / ("." + target.filename().string() + ".tmpXXXXXX")).string();
  std::vector<char> buffer(pattern.begin(), pattern.end());
  buffer.push_back('\0');
  const int fd = ::mkstemp(buffer.data());
  if (fd < 0) throw ioError("cannot create a temporary file for", path);
  // mkstemp creates the file 0600; give the output the permissions of any new file instead.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::fchmod(fd, 0666 & ~mask);
  ::close(fd);
  return std::string(buffer.data());
}

void commitTemporary(const std::string& temporaryPath, const std::string& path) {
  if (std::rename(temporaryPath.c_str(), path.c_str()) != 0) {
    const std::runtime_error error = ioError("cannot write", path);
    std::remove(temporaryPath.c_str());
    throw error;
  }
}

void writeFileAtomically(const std::string& path, const std::string& content) {
  const std::string temporary = makeTemporaryBeside(path);
  std::FILE* file = std::fopen(temporary.c_str(), "wb");
  bool ok = file != nullptr;
  if (ok) ok = std::fwrite(content.data(), 1, content.size(), file) == content.size();
  if (file != nullptr) ok = (std::fflush(file) == 0) && ok && (::fsync(fileno(file)) == 0);
  if (file != nullptr) ok = (std::fclose(file) == 0) && ok;
  if (!ok) {
    const std::runtime_error error = ioError("cannot write", path);
    std::remove(temporary.c_str());
    throw error;
  }
  commitTemporary(temporary, path);
}

}  // namespace boxsim
