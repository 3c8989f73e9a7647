/// \file
/// Number formatting shared by every output file; the order of a patch outline.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <utility>

#include "boxsim/core/math.hpp"

namespace boxsim {

std::string shortestText(double value) {
  char buffer[32];
#if defined(__cpp_lib_to_chars)
  const std::to_chars_result r = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, r.ptr);
#else
  // A C++ library without std::to_chars for doubles (Emscripten's libc++, for the browser
  // demo): the fewest %g digits that read back as the same double. The same digits, though
  // large and small numbers may come in exponent form where to_chars writes them out.
  for (int digits = 1;; ++digits) {
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
    if (digits == 17 || std::strtod(buffer, nullptr) == value || std::isnan(value)) return buffer;
  }
#endif
}

std::array<int, 4> counterClockwiseOrder(const std::array<Eigen::Vector2d, 4>& q, int count) {
  std::array<int, 4> order{0, 1, 2, 3};
  std::array<double, 4> angle{};
  for (int k = 0; k < count; ++k) angle[k] = std::atan2(q[k].y(), q[k].x());
  // Insertion sort of at most four: stable, so equal angles keep their index order.
  for (int i = 1; i < count; ++i)
    for (int k = i; k > 0 && angle[order[k]] < angle[order[k - 1]]; --k) std::swap(order[k], order[k - 1]);
  return order;
}

}  // namespace boxsim
