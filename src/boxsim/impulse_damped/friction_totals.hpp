/// \file
/// The impulses each touching pair has received in the current step: the budget of its Coulomb
/// friction (applyPatchFriction in core/newtonian_impulse.hpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <unordered_map>

#include "boxsim/core/newtonian_impulse.hpp"

namespace boxsim {

/// Per pair of bodies (a < b), the normal impulse, the friction impulse and the torsional
/// friction impulse applied to its contact since the step began (FrictionSum). Lookups only:
/// no iteration order reaches the physics, so the hash map keeps runs deterministic.
class FrictionTotals {
 public:
  /// The sums of the pair (a, b), created empty on first use.
  FrictionSum& at(int a, int b) {
    return sums_[(static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
                 static_cast<std::uint32_t>(b)];
  }
  /// Forgets every pair: called as a step begins.
  void clear() { sums_.clear(); }

 private:
  std::unordered_map<std::uint64_t, FrictionSum> sums_;
};

}  // namespace boxsim
