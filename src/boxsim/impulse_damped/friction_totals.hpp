/// \file
/// The impulses each touching pair has received in the current step: the budget of its Coulomb
/// friction (applyPatchFriction in core/newtonian_impulse.hpp).
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include "boxsim/core/newtonian_impulse.hpp"
#include "boxsim/core/pair_table.hpp"
#include "boxsim/core/world.hpp"
#include "boxsim/impulse_damped/contact_normal.hpp"

namespace boxsim {

/// Per pair of bodies (a < b), the normal impulse, the friction impulse and the torsional
/// friction impulse applied to its contact since the step began (FrictionSum). Lookups only:
/// no iteration order reaches the physics, so the table (PairTable) keeps runs deterministic;
/// it keeps its memory from step to step.
class FrictionTotals {
 public:
  /// The sums of the pair (a, b), created empty on first use. Every pass asks for its contacts'
  /// pairs in about the order the pass before did, and the sums stand in the order they were
  /// first asked for: the place after the last one asked for is tried before the table's lookup.
  FrictionSum& at(int a, int b) {
    if (!sums_.holds(next_, a, b)) next_ = sums_.place(a, b);
    return sums_.value(next_++);
  }
  /// Forgets every pair, and the bodies' order by height: called as a step begins.
  void clear() {
    sums_.clear();
    next_ = 0;
    ordered_ = false;
  }

  /// The load each movable body puts on each of its supports among the frictional `contacts`
  /// of a pass (impulse or damped integration): its weight m |g| Δt (N s) plus the shares of the
  /// bodies it carries, spread over the contacts whose normal pushes it against gravity in
  /// proportion to how far each normal rises (n · up: a side contact carries nothing), worked
  /// out from the top down. The impulses say little of a resting body's load: in the passes
  /// before the last only a part of it, where the contact passes' restitution climbs from -1
  /// to 0 (\alg{RESOLVECONTACTS L5}); under damped integration none between two movable bodies,
  /// where the gravity trick (\alg{COLLIDE L1-L6}) adds g Δt to both and DAMPENOBJECTS (L6-L9)
  /// zeroes the vertical momentum a resting box would bring, and a geometrically stable body's
  /// vertical momentum is reset after every impulse (\alg{COLLIDE L11-L14}). Under the plain
  /// impulse step, shock propagation then freezes the lower box of a stack before its upper one
  /// is settled: two flat boxes on a plank tilted 30° (μ 0.8 between them, 0.5 on the plank)
  /// slid 0.47 m in 2 s on the impulses' budget where Coulomb slides them 1.33 m.
  void shareWeights(const World& world, const std::vector<ImpulseContact>& contacts, double dt);
  /// The least friction budget (N s) of `contact` for the body it supports: the contact's part of
  /// that body's load (shareWeights) times |n · up|, the part pressed along the normal
  /// (m g cos θ Δt for a box alone on a plank tilted by θ); 0 when it supports none.
  double supportShare(const ImpulseContact& contact) const;
  /// g Δt (m/s) of the last shareWeights.
  double restingSpeed() const { return restingSpeed_; }

 private:
  PairTable<FrictionSum> sums_;
  std::size_t next_ = 0;  ///< the place after the one at() gave last
  /// A contact that carries a body: the body, the one under it, and how far its normal rises.
  struct Edge {
    int carried;  ///< body index
    int under;    ///< body index
    double rise;  ///< |n · up|
  };
  std::vector<double> share_;   ///< per body, N s: its load per unit rise of its supports
  std::vector<double> rises_;   ///< per body: the sum of its supports' rises
  std::vector<int> shared_;     ///< the bodies whose share_ is set
  std::vector<double> height_;  ///< per body of shared_, m: its centre's height along up_
  /// Sorts shared_ from the highest body down (ties by index), from the order of every body by
  /// height kept for the step (byHeight_), made anew when a body to sort stands elsewhere.
  void sortByHeight(const World& world);
  std::vector<int> byHeight_;         ///< every body, highest first (ties by index)
  std::vector<double> orderHeight_;   ///< per body, m: the height byHeight_ was made with
  bool ordered_ = false;              ///< byHeight_ was made in this step
  /// Groups edges_ by carried body (grouped_, edgeStart_, edgeCount_), each group in
  /// increasing order of the body under it: the order a sort by (carried, under) gives.
  void groupEdges();
  std::vector<Edge> edges_;     ///< the carrying contacts, in the order of the contacts
  std::vector<Edge> grouped_;   ///< edges_ grouped (groupEdges)
  std::vector<std::size_t> edgeStart_;  ///< per body of shared_: its group's first place
  std::vector<std::size_t> edgeCount_;  ///< per body: its group's size (0 outside shared_)
  Vec3 up_ = Vec3::UnitY();     ///< against gravity
  double restingSpeed_ = 0.0;   ///< m/s, g Δt
};

}  // namespace boxsim
