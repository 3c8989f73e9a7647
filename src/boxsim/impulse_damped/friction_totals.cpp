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
  }
  shared_.clear();
  edges_.clear();
  const std::size_t n = world.bodies.size();
  share_.resize(n, 0.0);
  rises_.resize(n, 0.0);
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
  std::sort(shared_.begin(), shared_.end(),
            [&](int i, int j) { return height(i) > height(j) || (height(i) == height(j) && i < j); });
  std::sort(edges_.begin(), edges_.end(), [](const Edge& x, const Edge& y) {
    return x.carried < y.carried || (x.carried == y.carried && x.under < y.under);
  });
  for (int i : shared_) share_[static_cast<std::size_t>(i)] = world.bodies[i].mass * g * dt;
  for (int i : shared_) {
    const std::size_t k = static_cast<std::size_t>(i);
    share_[k] /= rises_[k];  // load per unit rise
    const auto first = std::lower_bound(edges_.begin(), edges_.end(), i,
                                        [](const Edge& e, int carried) { return e.carried < carried; });
    for (auto e = first; e != edges_.end() && e->carried == i; ++e) {
      const std::size_t under = static_cast<std::size_t>(e->under);
      // A lower body that is itself carried takes this contact's part of the load on.
      if (rises_[under] > 0.0 && height(e->under) < height(i)) share_[under] += share_[k] * e->rise;
    }
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
