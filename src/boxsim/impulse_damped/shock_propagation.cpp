/// \file
/// Shock propagation (Guendelman et al. 2003, §7).
#include "boxsim/impulse_damped/shock_propagation.hpp"

#include <algorithm>
#include <deque>
#include <tuple>

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/core/newtonian_impulse.hpp"
#include "boxsim/impulse_damped/impulse_pass.hpp"

namespace boxsim {

std::vector<int> contactLevels(const World& world, const std::vector<ImpulseContact>& contacts) {
  const int n = static_cast<int>(world.bodies.size());
  std::vector<std::vector<int>> neighbours(n);
  for (const ImpulseContact& c : contacts) {
    neighbours[c.a].push_back(c.b);
    neighbours[c.b].push_back(c.a);
  }
  std::vector<int> level(n, n);
  std::deque<int> queue;
  for (int i = 0; i < n; ++i)
    if (world.bodies[i].immovable) {
      level[i] = 0;
      queue.push_back(i);
    }
  while (!queue.empty()) {
    const int i = queue.front();
    queue.pop_front();
    for (int j : neighbours[i])
      if (level[j] == n && !world.bodies[j].immovable) {
        level[j] = level[i] + 1;
        queue.push_back(j);
      }
  }
  return level;
}

int propagateShock(World& world, double dt, double margin, ContactGathering& gathering,
                   FrictionTotals* totals) {
  std::vector<ImpulseContact>& contacts =
      gathering.begin(world, dt, GravityMode::VelocityNoGravity, margin);
  const std::vector<int> level = contactLevels(world, contacts);
  const auto key = [&](const ImpulseContact& c) {
    return std::make_tuple(std::max(level[c.a], level[c.b]), c.point.y(), c.a, c.b);
  };
  std::stable_sort(contacts.begin(), contacts.end(),
                   [&](const ImpulseContact& l, const ImpulseContact& r) { return key(l) < key(r); });
  int impulses = 0;
  for (const ImpulseContact& c : contacts) {
    RigidBody& a = world.bodies[c.a];
    RigidBody& b = world.bodies[c.b];
    double j = 0.0;
    if (level[c.a] == level[c.b]) {
      j = contactImpulse(a, b, c, 0.0, totals);
    } else {
      // The lower level has already been settled: it acts as if infinitely heavy. A copy with
      // zero inverse mass and inertia stands in for it, so only the upper body changes.
      const bool aLower = level[c.a] < level[c.b];
      RigidBody fixed = aLower ? a : b;
      fixed.invMass = 0.0;
      fixed.Iinv.setZero();
      fixed.immovable = true;
      j = aLower ? contactImpulse(fixed, b, c, 0.0, totals) : contactImpulse(a, fixed, c, 0.0, totals);
    }
    if (j > 0.0) ++impulses;
  }
  gathering.end(world);
  return impulses;
}

}  // namespace boxsim
