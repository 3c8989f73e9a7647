/// \file
/// Number formatting shared by every output file; the order of a patch outline.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <utility>

#include "boxsim/core/math.hpp"

namespace boxsim {

namespace {
/// Writes shortestText(value) into `buffer` (32 characters are room for any double) and
/// returns the end of the text.
char* writeShortestText(char (&buffer)[32], double value) {
#if defined(__cpp_lib_to_chars)
  return std::to_chars(buffer, buffer + sizeof buffer, value).ptr;
#else
  // A C++ library without std::to_chars for doubles (Emscripten's libc++, for the browser
  // demo): the fewest %g digits that read back as the same double. The same digits, though
  // large and small numbers may come in exponent form where to_chars writes them out.
  for (int digits = 1;; ++digits) {
    const int length = std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
    if (digits == 17 || std::strtod(buffer, nullptr) == value || std::isnan(value))
      return buffer + length;
  }
#endif
}
}  // namespace

std::string shortestText(double value) {
  char buffer[32];
  return std::string(buffer, writeShortestText(buffer, value));
}

void appendShortestText(std::string& out, double value) {
  char buffer[32];
  out.append(buffer, writeShortestText(buffer, value));
}

std::array<int, 4> counterClockwiseOrder(const std::array<Eigen::Vector2d, 4>& q, int count) {
  // The order of atan2(y, x), from −π up to π, by exact tests instead of the C library's atan2,
  // whose last bit differs between libraries: first the half plane (y < 0: (−π, 0); y ≥ 0:
  // [0, π]; y = 0 with x < 0 is π, last), then within a half plane the sign of the cross
  // product, which is positive when the first point comes first.
  const auto half = [&](int k) { return q[k].y() < 0.0 ? 0 : (q[k].y() == 0.0 && q[k].x() < 0.0 ? 2 : 1); };
  const auto before = [&](int a, int b) {
    if (half(a) != half(b)) return half(a) < half(b);
    return q[a].x() * q[b].y() - q[a].y() * q[b].x() > 0.0;
  };
  std::array<int, 4> order{0, 1, 2, 3};
  // Insertion sort of at most four: stable, so equal angles keep their index order.
  for (int i = 1; i < count; ++i)
    for (int k = i; k > 0 && before(order[k], order[k - 1]); --k) std::swap(order[k], order[k - 1]);
  return order;
}

}  // namespace boxsim
