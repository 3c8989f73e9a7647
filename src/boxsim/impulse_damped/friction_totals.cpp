/// \file
/// The step's friction sums and the loads resting contacts carry (friction_totals.hpp).
#include "boxsim/impulse_damped/friction_totals.hpp"

#include <algorithm>
#include <cmath>

namespace boxsim {

void FrictionTotals::shareWeights(const World& world, const std::vector<ImpulseContact>& contacts,
                                  double dt) {
  for (int i : shared_) {
    share_[static_cast<std::size_t>(i)] = 0.0;
    rises_[static_cast<std::size_t>(i)] = 0.0;
    edgeCount_[static_cast<std::size_t>(i)] = 0;
  }
  shared_.clear();
  edges_.clear();
  const std::size_t n = world.bodies.size();
  share_.resize(n, 0.0);
  rises_.resize(n, 0.0);
  edgeCount_.resize(n, 0);
  edgeStart_.resize(n, 0);
  const double g = world.gravity.norm();
  if (!(g > 0.0)) return;
  up_ = -world.gravity / g;
  restingSpeed_ = g * dt;
  // Each frictional contact whose normal pushes a movable body against gravity carries a part of
  // its load in proportion to how far the normal rises (n · up: a side contact carries none).
  for (const ImpulseContact& c : contacts) {
    if (c.friction.frictionless()) continue;
    const double rise = c.normal.dot(up_);  // the normal runs from a to b
    const int carried = rise > 0.0 ? c.b : rise < 0.0 ? c.a : -1;
    if (carried < 0 || world.bodies[carried].immovable) continue;
    edges_.push_back({carried, carried == c.b ? c.a : c.b, std::abs(rise)});
    const std::size_t k = static_cast<std::size_t>(carried);
    if (rises_[k] == 0.0) shared_.push_back(carried);
    rises_[k] += std::abs(rise);
  }
  if (shared_.empty()) return;
  // From the top down, each body's load (its weight and what the bodies it carries put on it)
  // is spread over its supports and passed on to the movable ones under it.
  height_.resize(n);
  for (int i : shared_) height_[static_cast<std::size_t>(i)] = up_.dot(world.bodies[i].s.x);
  const auto height = [&](int i) { return height_[static_cast<std::size_t>(i)]; };
  sortByHeight(world);
  // The carrying contacts grouped by the body they carry, each group by the body under it.
  groupEdges();
  for (int i : shared_) share_[static_cast<std::size_t>(i)] = world.bodies[i].mass * g * dt;
  for (int i : shared_) {
    const std::size_t k = static_cast<std::size_t>(i);
    share_[k] /= rises_[k];  // load per unit rise
    const auto first = grouped_.begin() + static_cast<std::ptrdiff_t>(edgeStart_[k]);
    const auto last = first + static_cast<std::ptrdiff_t>(edgeCount_[k]);
    for (auto e = first; e != last; ++e) {
      const std::size_t under = static_cast<std::size_t>(e->under);
      // A lower body that is itself carried takes this contact's part of the load on.
      if (rises_[under] > 0.0 && height(e->under) < height(i)) share_[under] += share_[k] * e->rise;
    }
  }
}

void FrictionTotals::sortByHeight(const World& world) {
  // The order of every body by height (highest first, then by index) is kept for the step:
  // the bodies stand where they stood in every pass. It stands while each body to sort has
  // the height it was ordered by, bit for bit; picking those bodies out of it is then the
  // sort of shared_ by the same comparison (a total order: no two bodies share an index).
  const std::size_t n = world.bodies.size();
  bool current = ordered_ && orderHeight_.size() == n;
  for (std::size_t k = 0; current && k < shared_.size(); ++k) {
    const std::size_t i = static_cast<std::size_t>(shared_[k]);
    current = sameBits(orderHeight_[i], height_[i]);
  }
  if (!current) {
    orderHeight_.resize(n);
    byHeight_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      orderHeight_[i] = up_.dot(world.bodies[i].s.x);
      byHeight_[i] = static_cast<int>(i);
    }
    const auto height = [&](int i) { return orderHeight_[static_cast<std::size_t>(i)]; };
    std::sort(byHeight_.begin(), byHeight_.end(), [&](int i, int j) {
      return height(i) > height(j) || (height(i) == height(j) && i < j);
    });
    ordered_ = true;
  }
  shared_.clear();
  for (int i : byHeight_)
    if (rises_[static_cast<std::size_t>(i)] > 0.0) shared_.push_back(i);
}

void FrictionTotals::groupEdges() {
  // A counting sort by carried body: each group's place, then the edges in their order.
  for (const Edge& e : edges_) ++edgeCount_[static_cast<std::size_t>(e.carried)];
  std::size_t place = 0;
  for (int i : shared_) {
    const std::size_t k = static_cast<std::size_t>(i);
    edgeStart_[k] = place;
    place += edgeCount_[k];
    edgeCount_[k] = 0;
  }
  grouped_.resize(edges_.size());
  for (const Edge& e : edges_) {
    const std::size_t k = static_cast<std::size_t>(e.carried);
    grouped_[edgeStart_[k] + edgeCount_[k]++] = e;
  }
  // Within a group by the body under it. Contacts come in (a, b) order, which puts a group in
  // that order already (the pairs (u, c) with u < c, then (c, u) with u > c), so this only checks.
  for (int i : shared_) {
    const std::size_t k = static_cast<std::size_t>(i);
    const auto first = grouped_.begin() + static_cast<std::ptrdiff_t>(edgeStart_[k]);
    const auto last = first + static_cast<std::ptrdiff_t>(edgeCount_[k]);
    for (auto e = first + (first != last); e < last; ++e)
      for (auto f = e; f != first && (f - 1)->under > f->under; --f) std::iter_swap(f - 1, f);
  }
}

double FrictionTotals::supportShare(const ImpulseContact& contact) const {
  if (shared_.empty()) return 0.0;
  const double rise = contact.normal.dot(up_);
  const int i = rise > 0.0 ? contact.b : rise < 0.0 ? contact.a : -1;
  if (i < 0 || static_cast<std::size_t>(i) >= share_.size()) return 0.0;
  // This contact's part of the load, rise / Σ rise, pressed along its normal (times rise again):
  // m g cos θ Δt for a box alone on a plank tilted by θ.
  return share_[static_cast<std::size_t>(i)] * rise * rise;
}

}  // namespace boxsim
