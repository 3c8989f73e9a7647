/// \file
/// The impulses each touching pair has received in the current step: the budget of its Coulomb
/// friction (applyPatchFriction in core/newtonian_impulse.hpp).
#pragma once

#include "boxsim/core/newtonian_impulse.hpp"
#include "boxsim/core/pair_table.hpp"

namespace boxsim {

/// Per pair of bodies (a < b), the normal impulse, the friction impulse and the torsional
/// friction impulse applied to its contact since the step began (FrictionSum). Lookups only:
/// no iteration order reaches the physics, so the table (PairTable) keeps runs deterministic;
/// it keeps its memory from step to step.
class FrictionTotals {
 public:
  /// The sums of the pair (a, b), created empty on first use.
  FrictionSum& at(int a, int b) { return sums_.at(a, b); }
  /// Forgets every pair: called as a step begins.
  void clear() { sums_.clear(); }

 private:
  PairTable<FrictionSum> sums_;
};

}  // namespace boxsim
