/// \file
/// Number formatting shared by every output file.
#include <charconv>

#include "boxsim/core/math.hpp"

namespace boxsim {

std::string shortestText(double value) {
  char buffer[32];
  const std::to_chars_result r = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, r.ptr);
}

}  // namespace boxsim
