/// \file
/// Islands of the step's contact graph (contact_islands.hpp).
#include "boxsim/impulse_damped/contact_islands.hpp"

#include <algorithm>
#include <numeric>
#include <utility>

namespace boxsim {

void ContactIslands::reset(const std::vector<char>& movable) {
  reset(movable.size());
  movable_.assign(movable.begin(), movable.end());
}

void ContactIslands::reset(std::size_t n) {
  parent_.resize(n);
  std::iota(parent_.begin(), parent_.end(), 0);
  size_.assign(n, 1);
  movable_.assign(n, 1);
  settled_.assign(n, 0);
  changed_.assign(n, 0);
}

std::size_t ContactIslands::rootFar(std::size_t k) {
  // Path halving: every other body on the way points to its grandparent.
  while (parent_[k] != static_cast<int>(k)) {
    parent_[k] = parent_[static_cast<std::size_t>(parent_[k])];
    k = static_cast<std::size_t>(parent_[k]);
  }
  return k;
}

void ContactIslands::flatten() {
  for (std::size_t k = 0; k < parent_.size(); ++k)
    parent_[k] = static_cast<int>(root(static_cast<int>(k)));
}

void ContactIslands::join(int a, int b) {
  const auto ua = static_cast<std::size_t>(a), ub = static_cast<std::size_t>(b);
  if (!movable_[ua] || !movable_[ub]) return;
  std::size_t ra = root(a), rb = root(b);
  if (ra == rb) return;
  // The larger island keeps its root (the lower index on a tie), so the paths stay short.
  if (size_[ra] < size_[rb] || (size_[ra] == size_[rb] && rb < ra)) std::swap(ra, rb);
  parent_[rb] = static_cast<int>(ra);
  size_[ra] += size_[rb];
  settled_[ra] = static_cast<char>(settled_[ra] && settled_[rb]);
  changed_[ra] = static_cast<char>(changed_[ra] || changed_[rb]);
}

void ContactIslands::markChanged(int i) {
  if (movable_[static_cast<std::size_t>(i)]) changed_[root(i)] = 1;
}

bool ContactIslands::settleUnchanged() {
  bool all = true;
  for (std::size_t k = 0; k < parent_.size(); ++k) {
    if (!movable_[k] || parent_[k] != static_cast<int>(k)) continue;
    if (!changed_[k]) settled_[k] = 1;
    changed_[k] = 0;
    all = all && settled_[k];
  }
  return all;
}

void ContactIslands::activateAll() {
  std::fill(settled_.begin(), settled_.end(), 0);
  std::fill(changed_.begin(), changed_.end(), 0);
}

}  // namespace boxsim
