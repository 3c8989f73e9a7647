/// \file
/// Number formatting shared by every output file; the order of a patch outline.
#include <charconv>
#include <cmath>
#include <utility>

#include "boxsim/core/math.hpp"

namespace boxsim {

std::string shortestText(double value) {
  char buffer[32];
  const std::to_chars_result r = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, r.ptr);
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
