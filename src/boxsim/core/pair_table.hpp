/// \file
/// A table of values by pair of body indices, for what a step keeps per pair (the friction
/// sums of a step): open addressing with linear probing over a flat array, values in the order
/// they were first asked for. It keeps its memory when it is emptied, so a step that asks for
/// about the pairs the last one did allocates nothing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace boxsim {

/// Values of type T by ordered pair (i, j) of body indices (i, j >= 0). Lookups go by key
/// only, so the table's layout never decides a result. References to values stay valid until
/// the next insertion or clear().
template <class T>
class PairTable {
 public:
  /// The value of (i, j), default-constructed and inserted when absent.
  T& at(int i, int j) { return values_[place(i, j)]; }
  /// The value of (i, j), or nullptr when absent; inserts nothing.
  const T* find(int i, int j) const {
    const long p = placeOf(i, j);
    return p >= 0 ? &values_[static_cast<std::size_t>(p)] : nullptr;
  }
  /// The place of (i, j)'s value, its value default-constructed and inserted when absent: the
  /// number of values inserted before it. A place stays the pair's until clear(), so a caller
  /// that asks for a pair many times can keep its place and reach the value without a lookup.
  std::size_t place(int i, int j) {
    if (2 * (keys_.size() + 1) > slots_.size()) rebuild(slots_.empty() ? 64 : 2 * slots_.size());
    const std::uint64_t key = keyOf(i, j);
    Slot& slot = slots_[slotOf(key)];
    if (slot.index != 0) return slot.index - 1;
    keys_.push_back(key);
    values_.emplace_back();
    slot = Slot{key, static_cast<std::uint32_t>(keys_.size())};
    return keys_.size() - 1;
  }
  /// The place of (i, j)'s value (place()), or -1 when absent; inserts nothing.
  long placeOf(int i, int j) const {
    if (slots_.empty()) return -1;
    const Slot& slot = slots_[slotOf(keyOf(i, j))];
    return static_cast<long>(slot.index) - 1;
  }
  /// Whether place `p` holds the value of (i, j): a caller that expects the pair there (one that
  /// asks for the pairs in about the order it asked before) checks so without a lookup.
  bool holds(std::size_t p, int i, int j) const { return p < keys_.size() && keys_[p] == keyOf(i, j); }
  /// The value at place `p` (place(), placeOf()).
  T& value(std::size_t p) { return values_[p]; }
  /// The value at place `p` (place(), placeOf()).
  const T& value(std::size_t p) const { return values_[p]; }
  /// Number of values.
  std::size_t size() const { return keys_.size(); }
  /// Exchanges the contents of two tables.
  void swap(PairTable& other) noexcept {
    keys_.swap(other.keys_);
    values_.swap(other.values_);
    slots_.swap(other.slots_);
    std::swap(shift_, other.shift_);
  }
  /// Forgets every value.
  void clear() {
    keys_.clear();
    values_.clear();
    slots_.assign(slots_.size(), Slot{});
  }

 private:
  static std::uint64_t keyOf(int i, int j) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(i)) << 32) |
           static_cast<std::uint32_t>(j);
  }
  /// A slot of the table: a key and 1 + the index of its value, or index 0 when empty. The key
  /// sits in the slot so that probing reads the table alone.
  struct Slot {
    std::uint64_t key = 0;
    std::uint32_t index = 0;
  };
  /// The slot holding `key`, or the empty one where it would go: Fibonacci hashing (the top
  /// bits of key times 2⁶⁴/φ), then linear probing.
  std::size_t slotOf(std::uint64_t key) const {
    const std::size_t mask = slots_.size() - 1;
    std::size_t slot = static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> shift_);
    while (slots_[slot].index != 0 && slots_[slot].key != key) slot = (slot + 1) & mask;
    return slot;
  }
  /// A table of `capacity` slots (a power of two, at least 2) holding every key.
  void rebuild(std::size_t capacity) {
    slots_.assign(capacity, Slot{});
    shift_ = 64;
    for (std::size_t c = capacity; c > 1; c >>= 1) --shift_;
    for (std::size_t e = 0; e < keys_.size(); ++e)
      slots_[slotOf(keys_[e])] = Slot{keys_[e], static_cast<std::uint32_t>(e + 1)};
  }

  std::vector<std::uint64_t> keys_;
  std::vector<T> values_;
  std::vector<Slot> slots_;  ///< at most half full
  int shift_ = 64;           ///< 64 - log2(slots_.size())
};

}  // namespace boxsim
