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

int KeptNarrowPhase::find(int i, int j) const {
  if (static_cast<std::size_t>(i) >= kept_.size()) return -1;
  const std::vector<Entry>& list = kept_[static_cast<std::size_t>(i)];
  const auto found = std::find_if(list.begin(), list.end(), [j](const Entry& e) { return e.j == j; });
  return found == list.end() ? -1 : static_cast<int>(found - list.begin());
}

int KeptNarrowPhase::place(int i, const Obb& a, int j, const Obb& b, bool& test) {
  const long versionA = versionOf(i, a), versionB = versionOf(j, b);
  std::vector<Entry>& list = kept_[static_cast<std::size_t>(i)];
  const int found = find(i, j);
  if (found >= 0 && list[static_cast<std::size_t>(found)].versionA == versionA &&
      list[static_cast<std::size_t>(found)].versionB == versionB) {
    list[static_cast<std::size_t>(found)].step = step_ + 1;
    ++reuses_;
    test = false;
    return found;
  }
  const Entry placed{j, step_ + 1, versionA, versionB, SeparatingAxisResult{}, false};
  ++tests_;
  test = true;
  if (found >= 0) {
    list[static_cast<std::size_t>(found)] = placed;
    return found;
  }
  list.push_back(placed);
  clipsOf_[static_cast<std::size_t>(i)].emplace_back();
  return static_cast<int>(list.size()) - 1;
}

KeptNarrowPhase::Entry& KeptNarrowPhase::at(int i, int e) {
  return kept_[static_cast<std::size_t>(i)][static_cast<std::size_t>(e)];
}

int KeptNarrowPhase::entry(int i, const Obb& a, int j, const Obb& b) {
  bool test = false;
  const int e = place(i, a, j, b, test);
  if (test) at(i, e).result = separatingAxisTest(a, b);
  return e;
}

bool KeptNarrowPhase::apartAlong(int i, const Obb& a, int j, const Obb& b, double margin,
                                 int& e, double& depth) const {
  e = find(i, j);
  if (e < 0) return false;
  const SeparatingAxisResult& last =
      kept_[static_cast<std::size_t>(i)][static_cast<std::size_t>(e)].result;
  return last.depth < 0.0 && separatedBeyond(a, b, last, margin, SeparatingAxisParams{}, &depth);
}

ContactManifold KeptNarrowPhase::apartManifold(int i, int e, double depth) {
  Entry& entry = at(i, e);
  entry.step = step_ + 1;
  ++axisChecks_;
  ContactManifold apart;
  apart.normal = entry.result.normal;
  apart.kind = entry.result.kind;
  apart.depth = depth;
  return apart;
}

bool KeptNarrowPhase::clipWithin(int i, int e, const Obb& a, const Obb& b, double margin) {
  Entry& entry = at(i, e);
  // Nothing within the margin: buildContactManifold clips nothing either.
  if (entry.result.depth <= -margin || entry.clipped) return false;
  clipsOf_[static_cast<std::size_t>(i)][static_cast<std::size_t>(e)] =
      clipContact(a, b, entry.result);
  entry.clipped = true;
  return true;
}

ContactManifold KeptNarrowPhase::manifoldOf(int i, int e, const Obb& a, const Obb& b,
                                            double margin) {
  const Entry& entry = at(i, e);
  if (entry.result.depth <= -margin) return buildContactManifold(a, b, entry.result, margin);
  return manifoldWithin(clipsOf_[static_cast<std::size_t>(i)][static_cast<std::size_t>(e)],
                        margin);
}

SeparatingAxisResult KeptNarrowPhase::axis(int i, const Obb& a, int j, const Obb& b) {
  if (!keep_) {
    ++tests_;
    return separatingAxisTest(a, b);
  }
  return at(i, entry(i, a, j, b)).result;
}

ContactManifold KeptNarrowPhase::collide(int i, const Obb& a, int j, const Obb& b, double margin) {
  if (!keep_) {
    ++tests_;
    return buildContactManifold(a, b, separatingAxisTest(a, b), margin);
  }
  // Apart at its last test, and still apart beyond the margin along that test's axis: the test
  // would find no point either.
  int e = -1;
  double depth = 0.0;
  if (apartAlong(i, a, j, b, margin, e, depth)) return apartManifold(i, e, depth);
  e = entry(i, a, j, b);
  clips_ += clipWithin(i, e, a, b, margin);
  return manifoldOf(i, e, a, b, margin);
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
  int e = -1;
  if (apartAlong(r.i, boxOf(r.i), r.j, boxOf(r.j), r.margin, e, p.depth)) {
    p.state = Pending::Apart;
    p.entry = e;
  }
}

void KeptNarrowPhase::testAndClip(std::size_t w) {
  const std::size_t k = static_cast<std::size_t>(work_[w]);
  const Request& r = batch_[k];
  Pending& p = pending_[k];
  const Obb a = boxOf(r.i), b = boxOf(r.j);
  if (p.state == Pending::Test) at(r.i, p.entry).result = separatingAxisTest(a, b);
  p.clipped = clipWithin(r.i, p.entry, a, b, r.margin);
}

void KeptNarrowPhase::runBatch(const World& world) {
  world_ = &world;
  pending_.assign(batch_.size(), Pending{});
  // Round one, on the loop's threads, reading the store alone: the pairs apart at their last
  // test and still apart along its axis (collide's first question).
  run(batch_.size(), &KeptNarrowPhase::checkAxis);
  // In request order on this thread, as collide() would: the versions, the tests handed back,
  // and a place in the store for each test to run (its result is written there next).
  work_.clear();
  for (std::size_t k = 0; k < batch_.size(); ++k) {
    const Request& r = batch_[k];
    Pending& p = pending_[k];
    if (p.state == Pending::Apart) continue;
    bool test = false;
    p.entry = place(r.i, boxOf(r.i), r.j, boxOf(r.j), test);
    p.state = test ? Pending::Test : Pending::Kept;
    const Entry& e = at(r.i, p.entry);
    // A test to run, or a kept one within the margin and not clipped yet: next round's.
    if (test || (e.result.depth > -r.margin && !e.clipped)) work_.push_back(static_cast<int>(k));
  }
  // Round two, on the loop's threads: each test and clip into its own entry.
  run(work_.size(), &KeptNarrowPhase::testAndClip);
}

ContactManifold KeptNarrowPhase::answer(std::size_t k) {
  const Request& r = batch_[k];
  const Pending& p = pending_[k];
  if (p.state == Pending::Apart) return apartManifold(r.i, p.entry, p.depth);
  clips_ += p.clipped;
  return manifoldOf(r.i, p.entry, boxOf(r.i), boxOf(r.j), r.margin);
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
