#include "boxsim/cli/checks.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "boxsim/cli/exit_status.hpp"
#include "boxsim/core/math.hpp"

namespace boxsim::cli {

namespace fs = std::filesystem;

void requireReadableInput(const std::string& path, const std::string& what) {
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (!fs::exists(status))
    throw CommandError(what + " '" + path + "' does not exist; check the path",
                       ExitStatus::NoInput);
  if (fs::is_directory(status))
    throw CommandError(what + " '" + path + "' is a folder; give the path of a file in it",
                       ExitStatus::NoInput);
  if (!std::ifstream(path))
    throw CommandError(what + " '" + path + "' cannot be read: " + std::strerror(errno),
                       ExitStatus::NoInput);
}

void requireDistinctOutput(const std::string& output, const std::vector<std::string>& inputs) {
  for (const std::string& input : inputs) {
    std::error_code error;
    if (fs::equivalent(output, input, error) && !error)
      throw CommandError("the output '" + output + "' is the input '" + input +
                             "' itself, which writing it would destroy; give another --out",
                         ExitStatus::Usage);
  }
}

CLI::Validator finiteNumber(double lowest, bool inclusive, const std::string& unit) {
  const std::string range =
      std::string(inclusive ? ">= " : "> ") + shortestText(lowest) + " " + unit;
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        const bool whole = !text.empty() && end != nullptr && *end == '\0';
        if (whole && std::isfinite(value) && (inclusive ? value >= lowest : value > lowest))
          return {};
        return "'" + text + "' is not a finite number " + range;
      },
      "NUMBER " + range);
}

}  // namespace boxsim::cli
