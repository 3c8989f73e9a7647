/// \file
/// The narrow phases of a step, kept (kept_narrow_phase.hpp).
#include "boxsim/collision/kept_narrow_phase.hpp"

#include <algorithm>
#include <cstring>

namespace boxsim {

namespace {
/// Whether n doubles are the same bit for bit (a -0 is not a +0, a NaN is itself).
bool sameBits(const double* x, const double* y, int n) {
  for (int k = 0; k < n; ++k) {
    std::uint64_t u, v;
    std::memcpy(&u, x + k, sizeof u);
    std::memcpy(&v, y + k, sizeof v);
    if (u != v) return false;
  }
  return true;
}

/// Whether two boxes are the same bit for bit (so the test of either gives the same bits). The
/// centre first: it is what differs when a box has moved.
bool sameBox(const Obb& x, const Obb& y) {
  return sameBits(x.center.data(), y.center.data(), 3) &&
         sameBits(x.axes.data(), y.axes.data(), 9) &&
         sameBits(x.halfExtents.data(), y.halfExtents.data(), 3);
}

/// The key of the ordered pair (i, j).
std::uint64_t pairKey(int i, int j) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(i)) << 32) |
         static_cast<std::uint32_t>(j);
}
}  // namespace

std::size_t KeptNarrowPhase::slotOf(std::uint64_t key) const {
  // Fibonacci hashing into the table, then linear probing: the first slot that is empty or
  // holds the key.
  const std::size_t mask = slots_.size() - 1;
  std::size_t slot = static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> 32) & mask;
  while (slots_[slot] != 0 && entries_[slots_[slot] - 1].key != key) slot = (slot + 1) & mask;
  return slot;
}

void KeptNarrowPhase::rebuildSlots(std::size_t capacity) {
  slots_.assign(capacity, 0);
  for (std::size_t e = 0; e < entries_.size(); ++e)
    slots_[slotOf(entries_[e].key)] = static_cast<std::uint32_t>(e + 1);
}

SeparatingAxisResult KeptNarrowPhase::axis(int i, const Obb& a, int j, const Obb& b) {
  ++asked_;
  if (!keep_) {
    ++tests_;
    return separatingAxisTest(a, b);
  }
  // At most half full, so that probes stay short.
  if (2 * (entries_.size() + 1) > slots_.size())
    rebuildSlots(std::max<std::size_t>(64, 2 * slots_.size()));
  const std::uint64_t key = pairKey(i, j);
  const std::size_t slot = slotOf(key);
  if (slots_[slot] != 0) {
    Entry& entry = entries_[slots_[slot] - 1];
    entry.step = step_ + 1;
    if (sameBox(entry.a, a) && sameBox(entry.b, b)) {
      ++reuses_;
      return entry.result;
    }
    entry.a = a;
    entry.b = b;
    entry.result = separatingAxisTest(a, b);
    ++tests_;
    return entry.result;
  }
  entries_.push_back(Entry{key, step_ + 1, a, b, separatingAxisTest(a, b)});
  slots_[slot] = static_cast<std::uint32_t>(entries_.size());
  ++tests_;
  return entries_.back().result;
}

void KeptNarrowPhase::endStep() {
  ++step_;
  // An entry holds the step after the one it was last asked for in: keep those asked for in
  // the step that ends, in the order they came, and find them again in a table of the same
  // size (no allocation once the store has grown to the scene).
  std::size_t kept = 0;
  for (Entry& entry : entries_)
    if (entry.step >= step_) entries_[kept++] = entry;
  entries_.resize(kept);
  if (!slots_.empty()) rebuildSlots(slots_.size());
}

void KeptNarrowPhase::clear() {
  entries_.clear();
  slots_.clear();
}

}  // namespace boxsim
