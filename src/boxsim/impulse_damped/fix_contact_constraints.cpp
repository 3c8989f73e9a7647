/// \file
/// FIXCONTACTCONSTRAINTS (\alg{A.2}, \thesis{§4.4}).
#include "boxsim/impulse_damped/fix_contact_constraints.hpp"

#include <algorithm>
#include <tuple>

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/collision/separating_axis.hpp"

namespace boxsim {

int fixContactConstraints(World& world, double margin, const FixContactParams& params,
                          std::vector<ContactManifold>* gathered,
                          const std::vector<std::pair<int, int>>* pairs) {
  // A.2 L1: sortContactPointsAscending.
  std::vector<ContactManifold> contacts =
      pairs ? findContacts(world, margin, *pairs) : findContacts(world, margin);
  if (gathered) *gathered = contacts;
  const auto key = [](const ContactManifold& m) { return std::make_tuple(m.centroid().y(), m.a, m.b); };
  std::stable_sort(contacts.begin(), contacts.end(),
                   [&](const ContactManifold& l, const ContactManifold& r) { return key(l) < key(r); });
  int nudges = 0;
  for (const ContactManifold& c : contacts) {
    // A.2 L3-L5: the upper body moves, along the normal pointing from the lower one to it.
    const bool aUpper = world.bodies[c.a].s.x.y() > world.bodies[c.b].s.x.y();
    const int upper = aUpper ? c.a : c.b;
    const int lower = aUpper ? c.b : c.a;
    RigidBody& moving = world.bodies[upper];
    if (moving.immovable) continue;
    const Vec3 offset = aUpper ? Vec3(-c.normal) : Vec3(c.normal);
    const double ell = moving.halfExtents.minCoeff();
    const Obb stable = Obb::of(world.bodies[lower]);
    // A.2 L6-L7: nudge while they still intersect (beyond the documented slop).
    for (int n = 0; n < params.maxNudges; ++n) {
      if (separatingAxisTest(Obb::of(moving), stable).depth <= params.slop * ell) break;
      moving.s.x += params.nudge * ell * offset;  // x alone: nothing derived changes
      ++nudges;
    }
  }
  return nudges;
}

}  // namespace boxsim
