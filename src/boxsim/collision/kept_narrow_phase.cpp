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

int KeptNarrowPhase::find(int i, int j) const {
  if (static_cast<std::size_t>(i) >= kept_.size()) return -1;
  const std::vector<Entry>& list = kept_[static_cast<std::size_t>(i)];
  const auto found = std::find_if(list.begin(), list.end(), [j](const Entry& e) { return e.j == j; });
  return found == list.end() ? -1 : static_cast<int>(found - list.begin());
}

void KeptNarrowPhase::run(std::size_t count, void (KeptNarrowPhase::*item)(std::size_t)) {
  // The call captures the store alone: a std::function holds it without allocating. A batch
  // comes here only with a loop (collideAll).
  item_ = item;
  const std::function<void(int)> call = [this](int k) {
    (this->*item_)(static_cast<std::size_t>(k));
  };
  loop_(static_cast<int>(count), call);
}

void KeptNarrowPhase::checkAxis(std::size_t k) {
  const Request& r = batch_[k];
  Pending& p = pending_[k];
  const int e = find(r.i, r.j);
  if (e < 0) return;
  const SeparatingAxisResult& last =
      kept_[static_cast<std::size_t>(r.i)][static_cast<std::size_t>(e)].result;
  if (last.depth < 0.0 && separatedBeyond(boxOf(r.i), boxOf(r.j), last, r.margin,
                                          SeparatingAxisParams{}, &p.depth)) {
    p.state = Pending::Apart;
    p.entry = e;
  }
}

void KeptNarrowPhase::testAndClip(std::size_t w) {
  const std::size_t k = static_cast<std::size_t>(work_[w]);
  const Request& r = batch_[k];
  Pending& p = pending_[k];
  const std::size_t i = static_cast<std::size_t>(r.i), e = static_cast<std::size_t>(p.entry);
  Entry& entry = kept_[i][e];
  const Obb a = boxOf(r.i), b = boxOf(r.j);
  if (p.state == Pending::Test) entry.result = separatingAxisTest(a, b);
  if (entry.result.depth > -r.margin && !entry.clipped) {
    clipsOf_[i][e] = clipContact(a, b, entry.result);
    entry.clipped = true;
    p.clipped = true;
  }
}

void KeptNarrowPhase::runBatch(const World& world) {
  world_ = &world;
  pending_.assign(batch_.size(), Pending{});
  if (!keep_) return;
  // Round one, on the loop's threads, reading the store alone: the pairs apart at their last
  // test and still apart along its axis (collide's first question).
  run(batch_.size(), &KeptNarrowPhase::checkAxis);
  // In request order on this thread, as entry() would: the versions, the tests handed back,
  // and a place in the store for each test to run (its result is written there next).
  work_.clear();
  for (std::size_t k = 0; k < batch_.size(); ++k) {
    const Request& r = batch_[k];
    Pending& p = pending_[k];
    if (p.state == Pending::Apart) continue;
    const long versionA = versionOf(r.i, boxOf(r.i)), versionB = versionOf(r.j, boxOf(r.j));
    std::vector<Entry>& list = kept_[static_cast<std::size_t>(r.i)];
    p.entry = find(r.i, r.j);
    if (p.entry >= 0 && list[static_cast<std::size_t>(p.entry)].versionA == versionA &&
        list[static_cast<std::size_t>(p.entry)].versionB == versionB) {
      Entry& e = list[static_cast<std::size_t>(p.entry)];
      e.step = step_ + 1;
      ++reuses_;
      p.state = Pending::Kept;
      // Within the margin and not clipped yet: the clip is made next.
      if (e.result.depth > -r.margin && !e.clipped) work_.push_back(static_cast<int>(k));
      continue;
    }
    const Entry placed{r.j, step_ + 1, versionA, versionB, SeparatingAxisResult{}, false};
    ++tests_;
    if (p.entry >= 0) {
      list[static_cast<std::size_t>(p.entry)] = placed;
    } else {
      p.entry = static_cast<int>(list.size());
      list.push_back(placed);
      clipsOf_[static_cast<std::size_t>(r.i)].emplace_back();
    }
    work_.push_back(static_cast<int>(k));
  }
  // Round two, on the loop's threads: each test and clip into its own entry.
  run(work_.size(), &KeptNarrowPhase::testAndClip);
}

ContactManifold KeptNarrowPhase::answer(std::size_t k) {
  const Request& r = batch_[k];
  if (!keep_) return collide(r.i, boxOf(r.i), r.j, boxOf(r.j), r.margin);
  const Pending& p = pending_[k];
  const std::size_t i = static_cast<std::size_t>(r.i), e = static_cast<std::size_t>(p.entry);
  Entry& entry = kept_[i][e];
  if (p.state == Pending::Apart) {
    entry.step = step_ + 1;
    ++axisChecks_;
    ContactManifold apart;
    apart.normal = entry.result.normal;
    apart.kind = entry.result.kind;
    apart.depth = p.depth;
    return apart;
  }
  clips_ += p.clipped;
  if (entry.result.depth <= -r.margin)
    return buildContactManifold(boxOf(r.i), boxOf(r.j), entry.result, r.margin);
  return manifoldWithin(clipsOf_[i][e], r.margin);
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
