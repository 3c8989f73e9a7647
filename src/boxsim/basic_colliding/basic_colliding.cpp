/// \file
/// The basic colliding technique (\thesis{§2.1}).
#include "boxsim/basic_colliding/basic_colliding.hpp"

#include <stdexcept>
#include <vector>

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/core/newtonian_impulse.hpp"

namespace boxsim {

std::map<std::string, std::string> BasicCollidingStepper::parameters() const {
  return {{"integrator", integratorName(params_.integrator)},
          {"time_tolerance_s", shortestText(params_.timeOfImpact.timeTolerance)},
          {"depth_tolerance_m", shortestText(params_.timeOfImpact.depthTolerance)},
          {"max_events_per_step", std::to_string(params_.maxEventsPerStep)},
          {"max_impulse_passes", std::to_string(params_.maxImpulsePasses)}};
}

BasicCollidingStepper::BasicCollidingStepper(const BasicCollidingParams& params)
    : params_(params) {
  if (!(params.timeOfImpact.timeTolerance > 0.0))
    throw std::invalid_argument("basic_colliding: timeTolerance must be > 0 s");
  if (!(params.timeOfImpact.depthTolerance >= 0.0))
    throw std::invalid_argument("basic_colliding: depthTolerance must be >= 0 m");
  if (params.maxEventsPerStep < 1 || params.maxImpulsePasses < 1)
    throw std::invalid_argument("basic_colliding: maxEventsPerStep and maxImpulsePasses must be >= 1");
}

StepStats BasicCollidingStepper::step(World& world, double dt) {
  StepStats stats;
  // Bodies that gave up the rest of this step at the events limit; empty until one does.
  std::vector<char> held;
  int eventsSinceHold = 0;
  double remaining = dt;
  while (remaining > 0.0) {
    const WorldState start = world.saveState();
    // §2.1 step 1: integrate velocity and force forward in time.
    integrateWorld(world, remaining, params_.integrator, held);
    // §2.1 step 2: if two objects intersect, the simulation is stopped.
    const std::pair<int, int> first =
        firstIntersectingPair(world, params_.timeOfImpact.depthTolerance);
    if (first.first < 0) break;
    // §2.1 step 3: search backward and forward in time for the collision time (bisection);
    // the search leaves every body rolled back to just before the contact.
    const TimeOfImpact toi = findTimeOfImpact(world, start, remaining, first, params_.integrator,
                                              params_.timeOfImpact, held);
    stats.bisections += toi.bisections;
    stats.restarts += toi.restarts;
    // The contact geometry comes from the first intersecting state, the velocities from the
    // rolled-back one: the two differ by less than the time tolerance.
    World atImpact = world;
    atImpact.restoreState(start);
    integrateWorld(atImpact, toi.tIntersecting, params_.integrator, held);
    const std::vector<Collision> collisions = collisionsAt(atImpact);
    if (eventsSinceHold >= params_.maxEventsPerStep) {
      // The collisions have crowded together (§4.3 chattering): instead of hanging, hold the
      // bodies colliding now where they are for the rest of the step and let the others go on.
      // The focus pair always has a body still moving (it did not intersect at `start`), so
      // every hold takes at least one more body and the loop ends.
      if (held.empty()) held.assign(world.bodies.size(), 0);
      held[toi.pair.first] = !world.bodies[toi.pair.first].immovable;
      held[toi.pair.second] = !world.bodies[toi.pair.second].immovable;
      for (const Collision& c : collisions) {
        held[c.a] = !world.bodies[c.a].immovable;
        held[c.b] = !world.bodies[c.b].immovable;
      }
      stats.limitReached = true;
      eventsSinceHold = 0;
    } else {
      // §2.1 step 4: respond with Newtonian impulses, then integrate on from the contact time.
      // Every search counts as an event, even when no pair still approaches at the contact time
      // (a box resting on the ground, which this technique cannot hold up): counting searches
      // is what bounds the loop.
      resolveCollisions(world, collisions);
      ++stats.events;
      ++eventsSinceHold;
    }
    remaining -= toi.tSeparated;
  }
  stats.contacts = static_cast<int>(findContacts(world, params_.contactMargin).size());
  return stats;
}

std::vector<BasicCollidingStepper::Collision> BasicCollidingStepper::collisionsAt(
    const World& atImpact) const {
  // One contact point per colliding pair (A.2 L7 findContactPoint): the centroid of the
  // pair's contact manifold, so a box landing flat gets a pure linear impulse.
  std::vector<Collision> collisions;
  for (const ContactManifold& m : findContacts(atImpact)) {
    if (m.depth > params_.timeOfImpact.depthTolerance)
      collisions.push_back({m.a, m.b, m.centroid(), m.normal});
  }
  return collisions;
}

int BasicCollidingStepper::resolveCollisions(World& world,
                                             const std::vector<Collision>& collisions) const {
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
