/// \file
/// The narrow phases of a step, kept (kept_narrow_phase.hpp).
#include "boxsim/collision/kept_narrow_phase.hpp"

#include <cstring>
#include <iterator>

namespace boxsim {

namespace {
/// Whether two boxes are the same bit for bit (so the test of either gives the same bits).
bool sameBox(const Obb& x, const Obb& y) {
  return std::memcmp(x.center.data(), y.center.data(), sizeof(double) * 3) == 0 &&
         std::memcmp(x.axes.data(), y.axes.data(), sizeof(double) * 9) == 0 &&
         std::memcmp(x.halfExtents.data(), y.halfExtents.data(), sizeof(double) * 3) == 0;
}


/// The key of the ordered pair (i, j).
std::uint64_t pairKey(int i, int j) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(i)) << 32) |
         static_cast<std::uint32_t>(j);
}

}  // namespace

SeparatingAxisResult KeptNarrowPhase::axis(int i, const Obb& a, int j, const Obb& b) {
  if (!keep_) {
    ++tests_;
    return separatingAxisTest(a, b);
  }
  const auto same = kept_.find(pairKey(i, j));
  if (same != kept_.end() && sameBox(same->second.a, a) && sameBox(same->second.b, b)) {
    same->second.step = step_ + 1;
    ++reuses_;
    return same->second.result;
  }
  Entry& entry = same != kept_.end() ? same->second : kept_[pairKey(i, j)];
  entry.a = a;
  entry.b = b;
  entry.result = separatingAxisTest(a, b);
  entry.step = step_ + 1;
  ++tests_;
  return entry.result;
}

void KeptNarrowPhase::endStep() {
  ++step_;
  // An entry holds the step after the one it was last asked for in: keep those asked for in
  // the step that ends.
  for (auto it = kept_.begin(); it != kept_.end();)
    it = it->second.step < step_ ? kept_.erase(it) : std::next(it);
}

}  // namespace boxsim
