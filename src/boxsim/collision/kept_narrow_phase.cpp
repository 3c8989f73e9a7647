/// \file
/// The narrow phases of a step, kept (kept_narrow_phase.hpp).
#include "boxsim/collision/kept_narrow_phase.hpp"

#include <algorithm>

#include "boxsim/core/math.hpp"

namespace boxsim {

namespace {
/// Whether two boxes are the same bit for bit (so the test of either gives the same bits). The
/// centre first: it is what differs when a box has moved.
bool sameBox(const Obb& x, const Obb& y) {
  return sameBits(x.center, y.center) && sameBits(x.axes, y.axes) &&
         sameBits(x.halfExtents, y.halfExtents);
}
}  // namespace

long KeptNarrowPhase::versionOf(int body, const Obb& box) {
  const std::size_t k = static_cast<std::size_t>(body);
  if (k >= seen_.size()) {
    seen_.resize(k + 1);
    kept_.resize(k + 1);
  }
  Seen& seen = seen_[k];
  if (seen.version == 0 || !sameBox(seen.box, box)) {
    seen.box = box;
    seen.version = ++versions_;
  }
  return seen.version;
}

SeparatingAxisResult KeptNarrowPhase::axis(int i, const Obb& a, int j, const Obb& b) {
  if (!keep_) {
    ++tests_;
    return separatingAxisTest(a, b);
  }
  const long versionA = versionOf(i, a), versionB = versionOf(j, b);
  std::vector<Entry>& list = kept_[static_cast<std::size_t>(i)];
  auto entry = std::find_if(list.begin(), list.end(), [j](const Entry& e) { return e.j == j; });
  if (entry != list.end() && entry->versionA == versionA && entry->versionB == versionB) {
    entry->step = step_ + 1;
    ++reuses_;
    return entry->result;
  }
  const Entry ran{j, step_ + 1, versionA, versionB, separatingAxisTest(a, b)};
  if (entry == list.end())
    list.push_back(ran);
  else
    *entry = ran;
  ++tests_;
  return ran.result;
}

void KeptNarrowPhase::endStep() {
  ++step_;
  // An entry holds the step after the one it was last asked for in: keep those asked for in
  // the step that ends.
  for (std::vector<Entry>& list : kept_)
    list.erase(std::remove_if(list.begin(), list.end(),
                              [this](const Entry& e) { return e.step < step_; }),
               list.end());
}

}  // namespace boxsim
