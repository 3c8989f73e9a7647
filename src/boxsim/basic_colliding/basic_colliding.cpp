#include "boxsim/basic_colliding/basic_colliding.hpp"

#include <vector>

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/core/newtonian_impulse.hpp"

namespace boxsim {

std::map<std::string, std::string> BasicCollidingStepper::parameters() const {
  return {{"integrator", integratorName(params_.integrator)},
          {"time_tolerance_s", std::to_string(params_.timeOfImpact.timeTolerance)},
          {"depth_tolerance_m", std::to_string(params_.timeOfImpact.depthTolerance)},
          {"max_events_per_step", std::to_string(params_.maxEventsPerStep)},
          {"max_impulse_passes", std::to_string(params_.maxImpulsePasses)}};
}

StepStats BasicCollidingStepper::step(World& world, double dt) {
  StepStats stats;
  double remaining = dt;
  while (remaining > 0.0) {
    const WorldState start = world.saveState();
    // §2.1 step 1: integrate velocity and force forward in time.
    integrateWorld(world, remaining, params_.integrator);
    // §2.1 step 2: if two objects intersect, the simulation is stopped.
    const std::pair<int, int> first =
        firstIntersectingPair(world, params_.timeOfImpact.depthTolerance);
    if (first.first < 0) break;
    if (stats.events >= params_.maxEventsPerStep) {
      // The collisions have crowded together (§4.3 chattering): drop the rest of the step
      // rather than hang, leaving every body at its last collision-free state.
      world.restoreState(start);
      stats.limitReached = true;
      break;
    }
    // §2.1 step 3: search backward and forward in time for the collision time (bisection);
    // the search leaves every body rolled back to just before the contact.
    const TimeOfImpact toi = findTimeOfImpact(world, start, remaining, first,
                                              params_.integrator, params_.timeOfImpact);
    stats.bisections += toi.bisections;
    stats.restarts += toi.restarts;
    // The contact geometry comes from the first intersecting state, the velocities from the
    // rolled-back one: the two differ by less than the time tolerance.
    World atImpact = world;
    atImpact.restoreState(start);
    integrateWorld(atImpact, toi.tIntersecting, params_.integrator);
    // §2.1 step 4: respond with Newtonian impulses, then integrate on from the contact time.
    // Every search counts as an event, even when no pair still approaches at the contact time
    // (a box resting on the ground, which this technique cannot hold up): counting searches
    // is what bounds the loop.
    resolveCollisions(world, atImpact);
    ++stats.events;
    remaining -= toi.tSeparated;
  }
  stats.contacts = static_cast<int>(findContacts(world, params_.contactMargin).size());
  return stats;
}

int BasicCollidingStepper::resolveCollisions(World& world, const World& atImpact) const {
  // One contact point per colliding pair (A.2 L7 findContactPoint): the centroid of the
  // pair's contact manifold, so a box landing flat gets a pure linear impulse.
  struct Collision {
    int a, b;
    Vec3 point, normal;
  };
  std::vector<Collision> collisions;
  for (const ContactManifold& m : findContacts(atImpact)) {
    if (m.depth > params_.timeOfImpact.depthTolerance)
      collisions.push_back({m.a, m.b, m.centroid(), m.normal});
  }
  int impulses = 0;
  for (int pass = 0; pass < params_.maxImpulsePasses; ++pass) {
    int applied = 0;
    for (const Collision& c : collisions) {
      const double j = applyNewtonianImpulse(world.bodies[c.a], world.bodies[c.b], c.point,
                                             c.normal, world.restitution);
      if (j > 0.0) ++applied;
    }
    impulses += applied;
    if (applied == 0) break;
  }
  return impulses;
}

}  // namespace boxsim
