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
    clipsOf_.resize(k + 1);
  }
  Seen& seen = seen_[k];
  if (seen.version == 0 || !sameBox(seen.box, box)) {
    seen.box = box;
    seen.version = ++versions_;
  }
  return seen.version;
}

std::vector<KeptNarrowPhase::Entry>::iterator KeptNarrowPhase::entry(int i, const Obb& a, int j,
                                                                     const Obb& b) {
  const long versionA = versionOf(i, a), versionB = versionOf(j, b);
  std::vector<Entry>& list = kept_[static_cast<std::size_t>(i)];
  auto found = std::find_if(list.begin(), list.end(), [j](const Entry& e) { return e.j == j; });
  if (found != list.end() && found->versionA == versionA && found->versionB == versionB) {
    found->step = step_ + 1;
    ++reuses_;
    return found;
  }
  const Entry ran{j, step_ + 1, versionA, versionB, separatingAxisTest(a, b), false};
  ++tests_;
  if (found != list.end()) {
    *found = ran;
    return found;
  }
  list.push_back(ran);
  clipsOf_[static_cast<std::size_t>(i)].emplace_back();
  return list.end() - 1;
}

SeparatingAxisResult KeptNarrowPhase::axis(int i, const Obb& a, int j, const Obb& b) {
  if (!keep_) {
    ++tests_;
    return separatingAxisTest(a, b);
  }
  return entry(i, a, j, b)->result;
}

ContactManifold KeptNarrowPhase::collide(int i, const Obb& a, int j, const Obb& b, double margin) {
  if (!keep_) {
    ++tests_;
    return buildContactManifold(a, b, separatingAxisTest(a, b), margin);
  }
  // Apart at its last test, and still apart beyond the margin along that test's axis: the test
  // would find no point either.
  if (static_cast<std::size_t>(i) < kept_.size()) {
    std::vector<Entry>& list = kept_[static_cast<std::size_t>(i)];
    const auto last = std::find_if(list.begin(), list.end(), [j](const Entry& e) { return e.j == j; });
    double depth = 0.0;
    if (last != list.end() && last->result.depth < 0.0 &&
        separatedBeyond(a, b, last->result, margin, SeparatingAxisParams{}, &depth)) {
      last->step = step_ + 1;
      ++axisChecks_;
      ContactManifold apart;
      apart.normal = last->result.normal;
      apart.kind = last->result.kind;
      apart.depth = depth;
      return apart;
    }
  }
  const auto e = entry(i, a, j, b);
  // Nothing within the margin: buildContactManifold clips nothing either.
  if (e->result.depth <= -margin) return buildContactManifold(a, b, e->result, margin);
  std::vector<Entry>& list = kept_[static_cast<std::size_t>(i)];
  ClippedContact& clip = clipsOf_[static_cast<std::size_t>(i)][static_cast<std::size_t>(e - list.begin())];
  if (!e->clipped) {
    clip = clipContact(a, b, e->result);
    e->clipped = true;
    ++clips_;
  }
  return manifoldWithin(clip, margin);
}

void KeptNarrowPhase::endStep() {
  ++step_;
  // An entry holds the step after the one it was last asked for in: keep those asked for in
  // the step that ends, with their clips.
  for (std::size_t i = 0; i < kept_.size(); ++i) {
    std::vector<Entry>& list = kept_[i];
    std::vector<ClippedContact>& clips = clipsOf_[i];
    std::size_t to = 0;
    for (std::size_t from = 0; from < list.size(); ++from) {
      if (list[from].step < step_) continue;
      if (to != from) {
        list[to] = list[from];
        if (list[to].clipped) clips[to] = clips[from];
      }
      ++to;
    }
    list.resize(to);
    clips.resize(to);
  }
}

}  // namespace boxsim
