/// \file
/// Shock propagation (Guendelman et al. 2003, §7).
#include "boxsim/impulse_damped/shock_propagation.hpp"

#include <algorithm>
#include <tuple>

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/core/newtonian_impulse.hpp"
#include "boxsim/impulse_damped/impulse_pass.hpp"
#include "boxsim/impulse_damped/predicted_positions.hpp"

namespace boxsim {

void ShockLevels::compute(const World& world, const std::vector<ImpulseContact>& contacts) {
  const int n = static_cast<int>(world.bodies.size());
  // The contact graph as adjacency lists in one array: body i's neighbours are
  // neighbours_[start_[i] .. start_[i + 1]), in the order of `contacts`.
  start_.assign(static_cast<std::size_t>(n) + 1, 0);
  for (const ImpulseContact& c : contacts) {
    ++start_[static_cast<std::size_t>(c.a) + 1];
    ++start_[static_cast<std::size_t>(c.b) + 1];
  }
  for (int i = 0; i < n; ++i) start_[i + 1] += start_[i];
  neighbours_.resize(static_cast<std::size_t>(start_[n]));
  fill_.assign(start_.begin(), start_.end() - 1);
  for (const ImpulseContact& c : contacts) {
    neighbours_[static_cast<std::size_t>(fill_[c.a]++)] = c.b;
    neighbours_[static_cast<std::size_t>(fill_[c.b]++)] = c.a;
  }
  // Breadth first from the immovable bodies, in body order.
  level_.assign(static_cast<std::size_t>(n), n);
  queue_.clear();
  for (int i = 0; i < n; ++i)
    if (world.bodies[i].immovable) {
      level_[i] = 0;
      queue_.push_back(i);
    }
  for (std::size_t head = 0; head < queue_.size(); ++head) {
    const int i = queue_[head];
    for (int k = start_[i]; k < start_[i + 1]; ++k) {
      const int j = neighbours_[static_cast<std::size_t>(k)];
      if (level_[j] == n && !world.bodies[j].immovable) {
        level_[j] = level_[i] + 1;
        queue_.push_back(j);
      }
    }
  }
}

void ShockLevels::sort(const World& world, std::vector<ImpulseContact>& contacts) {
  compute(world, contacts);
  // (level, height, a, b) orders every pair of contacts: a pair of bodies has one contact.
  const auto key = [&](const ImpulseContact& c) {
    return std::make_tuple(std::max(level_[c.a], level_[c.b]), c.point.y(), c.a, c.b);
  };
  std::sort(contacts.begin(), contacts.end(),
            [&](const ImpulseContact& l, const ImpulseContact& r) { return key(l) < key(r); });
}

int propagateShock(World& world, double dt, double margin, ContactGathering& gathering,
                   FrictionTotals* totals) {
  std::vector<ImpulseContact>& contacts =
      gathering.begin(world, dt, GravityMode::VelocityNoGravity, margin);
  ShockLevels levels;
  levels.sort(world, contacts);
  const std::vector<int>& level = levels.levels();
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
      RigidBody fixed = heldCopy(aLower ? a : b);
      j = aLower ? contactImpulse(fixed, b, c, 0.0, totals) : contactImpulse(a, fixed, c, 0.0, totals);
    }
    if (j > 0.0) ++impulses;
  }
  gathering.end(world);
  return impulses;
}

int propagateShockDamped(World& world, double dt, double margin, ContactGathering& gathering,
                         const std::vector<char>& stable, double settledSpeed,
                         double restingSpeed, ShockLevels& levels, int iterations) {
  // Every pair of movable bodies that are all geometrically stable sits out (below): with no
  // other movable body, nothing is left to sweep, and no contact need be gathered.
  const auto isStable = [&](int i) {
    return !stable.empty() && stable[i] && !world.bodies[i].immovable;
  };
  const int n = static_cast<int>(world.bodies.size());
  bool anyUnstable = false;
  for (int i = 0; i < n && !anyUnstable; ++i)
    anyUnstable = !world.bodies[i].immovable && !isStable(i);
  if (!anyUnstable) return 0;
  std::vector<ImpulseContact>& contacts =
      gathering.begin(world, dt, GravityMode::VelocityPlusGravity, margin);
  levels.sort(world, contacts);
  const std::vector<int>& level = levels.levels();
  const Vec3 deltaV = gravityVelocity(world, GravityMode::VelocityPlusGravity, dt);
  // A contact this close to resting is left as it is: the rounding of the impulse that stopped
  // it, not an approach.
  const double still = 1e-6 * settledSpeed;
  std::vector<double>& sums = levels.sums();
  std::vector<char>& takes = levels.takes();
  sums.assign(contacts.size(), 0.0);
  takes.assign(contacts.size(), 0);
  const auto levelOf = [&](const ImpulseContact& c) { return std::max(level[c.a], level[c.b]); };
  int impulses = 0;
  for (std::size_t first = 0; first < contacts.size();) {
    std::size_t last = first + 1;
    while (last < contacts.size() && levelOf(contacts[last]) == levelOf(contacts[first])) ++last;
    for (int visit = 0; visit < iterations; ++visit) {
      bool changed = false;
      for (std::size_t k = first; k < last; ++k) {
        const ImpulseContact& c = contacts[k];
        RigidBody& a = world.bodies[c.a];
        RigidBody& b = world.bodies[c.b];
        if (visit == 0) {
          // A geometrically stable body's vertical momentum is reset after every COLLIDE
          // (L11-L14): its support is settled already. A pair of such bodies (or of one and an
          // immovable one) sits out.
          if ((a.immovable || isStable(c.a)) && (b.immovable || isStable(c.b))) continue;
          // A pair that approaches faster than a resting one is colliding, and one that
          // approaches slower than a settled one is settled: both are the passes' business.
          const double approach = approachSpeed(world, c, GravityMode::VelocityPlusGravity, dt);
          if (approach > restingSpeed || approach < settledSpeed) continue;
          takes[k] = 1;
        }
        if (!takes[k]) continue;
        // COLLIDE L1-L6: the velocity gravity is about to add, on both bodies.
        addVelocity(a, deltaV);
        addVelocity(b, deltaV);
        // The normal impulse alone, frictionless (see the declaration), restitution 0; the lower
        // body of a contact between levels held fixed.
        // A held body counts with its velocity and without its inverse mass (heldCopy's terms
        // of pairInverseMass are zeros).
        const bool holdA = level[c.a] < level[c.b], holdB = level[c.b] < level[c.a];
        const double vn = relativeNormalVelocity(a, b, c.ra, c.rb, c.normal);
        const double inverseMass =
            holdA   ? b.invMass + rotationalInverseMass(b.Iinv, c.rb, c.normal)
            : holdB ? a.invMass + rotationalInverseMass(a.Iinv, c.ra, c.normal)
                    : pairInverseMass(a, b, c.ra, c.rb, c.normal);
        double change = 0.0;
        if (inverseMass > 0.0 && (visit == 0 ? vn < 0.0 : std::abs(vn) > still)) {
          const double sum = std::max(0.0, sums[k] - vn / inverseMass);
          change = sum - sums[k];
          sums[k] = sum;
        }
        if (change != 0.0) {
          changed = true;
          // A held body's immovable copy takes its part of the impulse, which goes nowhere.
          if (holdA || holdB) {
            RigidBody held = heldCopy(holdA ? a : b);
            applyNormalImpulses(holdA ? held : a, holdB ? held : b, c.ra, c.rb, c.normal, change,
                                change);
          } else {
            applyNormalImpulses(a, b, c.ra, c.rb, c.normal, change, change);
          }
        }
        // COLLIDE L9-L14.
        addVelocity(a, -deltaV);
        addVelocity(b, -deltaV);
        for (int i : {c.a, c.b})
          if (isStable(i)) holdGeometricallyStable(world.bodies[i]);
        if (visit == 0 && change > 0.0) ++impulses;
      }
      if (!changed) break;
    }
    first = last;
  }
  gathering.end(world);
  return impulses;
}

}  // namespace boxsim
