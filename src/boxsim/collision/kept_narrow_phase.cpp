/// \file
/// The narrow phases of a step, kept (kept_narrow_phase.hpp).
#include "boxsim/collision/kept_narrow_phase.hpp"

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

SeparatingAxisResult KeptNarrowPhase::axis(int i, const Obb& a, int j, const Obb& b) {
  if (!keep_) {
    ++tests_;
    return separatingAxisTest(a, b);
  }
  bool inserted = false;
  Entry& entry = kept_.at(i, j, &inserted);
  entry.step = step_ + 1;
  if (!inserted && sameBox(entry.a, a) && sameBox(entry.b, b)) {
    ++reuses_;
    return entry.result;
  }
  entry.a = a;
  entry.b = b;
  entry.result = separatingAxisTest(a, b);
  ++tests_;
  return entry.result;
}

void KeptNarrowPhase::endStep() {
  ++step_;
  // An entry holds the step after the one it was last asked for in: keep those asked for in
  // the step that ends.
  kept_.retain([this](const Entry& entry) { return entry.step >= step_; });
}

}  // namespace boxsim
