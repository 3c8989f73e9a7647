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

std::string collisionLoopWorkLimit(const BasicCollidingParams& params) {
  return "at most " + std::to_string(params.maxEventsPerStep) +
         " collision events a step (max_events_per_step); collisions crowding together as "
         "bodies come to rest reach it (thesis §4.3)";
}

void requireCollisionLoopParams(const BasicCollidingParams& params, const std::string& method) {
  if (!(params.timeOfImpact.timeTolerance > 0.0))
    throw std::invalid_argument(method + ": timeTolerance must be > 0 s");
  if (!(params.timeOfImpact.depthTolerance >= 0.0))
    throw std::invalid_argument(method + ": depthTolerance must be >= 0 m");
  if (params.maxEventsPerStep < 1 || params.maxImpulsePasses < 1)
    throw std::invalid_argument(method + ": maxEventsPerStep and maxImpulsePasses must be >= 1");
}

BasicCollidingStepper::BasicCollidingStepper(const BasicCollidingParams& params)
    : params_(params) {
  requireCollisionLoopParams(params, "basic_colliding");
}

StepStats BasicCollidingStepper::step(World& world, double dt) {
  return advanceColliding(world, dt, params_);
}

namespace {

/// The pairs intersecting at the first overlapping state of a search, each with its impulse
/// points (the manifold centroid, or every manifold point) and normal; restitution not yet set.
std::vector<PairCollision> collisionsAt(const World& atImpact, double depthTolerance,
                                        bool everyPoint) {
  // One contact point per colliding pair (COLLIDE L7 findContactPoint): the centroid of the
  // pair's contact manifold, so a box landing flat gets a pure linear impulse. Or, for the
  // analytic method, every point of the manifold.
  std::vector<PairCollision> collisions;
  for (const ContactManifold& m : findContacts(atImpact)) {
    if (m.depth <= depthTolerance) continue;
    PairCollision c;
    c.a = m.a;
    c.b = m.b;
    c.normal = m.normal;
    if (everyPoint)
      for (int k = 0; k < m.count; ++k) c.points.push_back(m.points[k].position);
    else
      c.points.push_back(m.centroid());
    collisions.push_back(std::move(c));
  }
  return collisions;
}

/// Newtonian impulses for each collision whose bodies approach, in passes until none does; the
/// restitution of each point is fixed by its approach speed before the first pass. A pair's
/// points go to hooks.simultaneousImpulses when it is set, else its one point gets
/// applyNewtonianImpulse.
int resolveCollisions(World& world, std::vector<PairCollision>& collisions, int maxPasses,
                      const CollisionLoopHooks& hooks) {
  for (PairCollision& c : collisions) {
    c.restitution.assign(c.points.size(), world.restitution);
    if (!hooks.restitution) continue;
    for (std::size_t k = 0; k < c.points.size(); ++k) {
      const double speed =
          -relativeNormalVelocity(world.bodies[c.a], world.bodies[c.b], c.points[k], c.normal);
      c.restitution[k] = hooks.restitution(world, speed);
    }
  }
  int impulses = 0;
  for (int pass = 0; pass < maxPasses; ++pass) {
    int applied = 0;
    for (const PairCollision& c : collisions) {
      if (hooks.simultaneousImpulses) {
        applied += hooks.simultaneousImpulses(world, c);
        continue;
      }
      const double j = applyNewtonianImpulse(world.bodies[c.a], world.bodies[c.b], c.points[0],
                                             c.normal, c.restitution[0]);
      if (j > 0.0) ++applied;
    }
    impulses += applied;
    if (applied == 0) break;
  }
  return impulses;
}

}  // namespace

StepStats advanceColliding(World& world, double dt, const BasicCollidingParams& params,
                           const CollisionLoopHooks& hooks) {
  StepStats stats;
  // Bodies that gave up the rest of this step at the events limit; empty until one does.
  std::vector<char> held;
  int eventsSinceHold = 0;
  double remaining = dt;
  // Bodies integrateWorld advances: movable and not held.
  const auto moving = [&] {
    long count = 0;
    for (std::size_t k = 0; k < world.bodies.size(); ++k)
      count += !world.bodies[k].immovable && (held.empty() || !held[k]);
    return count;
  };
  while (remaining > 0.0) {
    const WorldState start = world.saveState();
    const std::vector<Wrench> extra = hooks.extraForces ? hooks.extraForces(world) : std::vector<Wrench>{};
    // §2.1 step 1: integrate velocity and force forward in time.
    integrateWorld(world, remaining, params.integrator, held, extra);
    stats.bodyIntegrations += moving();
    // §2.1 step 2: if two objects intersect, the simulation is stopped.
    const std::pair<int, int> first = firstIntersectingPair(
        world, params.timeOfImpact.depthTolerance, hooks.notColliding);
    if (first.first < 0) break;
    // §2.1 step 3: search backward and forward in time for the collision time (bisection);
    // the search leaves every body rolled back to just before the contact.
    const TimeOfImpact toi = findTimeOfImpact(world, start, remaining, first, params.integrator,
                                              params.timeOfImpact, held, extra, hooks.notColliding);
    stats.bisections += toi.bisections;
    stats.restarts += toi.restarts;
    // Each bisection rolls every moving body back to `start` and integrates it again; so does
    // the integration to the contact time below.
    stats.bodyRollbacks += moving() * (toi.bisections + 1);
    stats.bodyIntegrations += moving() * (toi.bisections + 1);
    // The contact geometry comes from the first intersecting state, the velocities from the
    // rolled-back one: the two differ by less than the time tolerance.
    World atImpact = world;
    atImpact.restoreState(start);
    integrateWorld(atImpact, toi.tIntersecting, params.integrator, held, extra);
    std::vector<PairCollision> collisions = collisionsAt(
        atImpact, params.timeOfImpact.depthTolerance, static_cast<bool>(hooks.simultaneousImpulses));
    if (eventsSinceHold >= params.maxEventsPerStep) {
      // The collisions have crowded together (§4.3 chattering): instead of hanging, hold the
      // bodies colliding now where they are for the rest of the step and let the others go on.
      // The focus pair always has a body still moving (it did not intersect at `start`), so
      // every hold takes at least one more body and the loop ends.
      if (held.empty()) held.assign(world.bodies.size(), 0);
      const long movingBefore = moving();
      held[toi.pair.first] = !world.bodies[toi.pair.first].immovable;
      held[toi.pair.second] = !world.bodies[toi.pair.second].immovable;
      for (const PairCollision& c : collisions) {
        held[c.a] = !world.bodies[c.a].immovable;
        held[c.b] = !world.bodies[c.b].immovable;
      }
      stats.limitReached = true;
      eventsSinceHold = 0;
      // A pair that already intersected at `start` (a body launched into one that had moved to
      // its launch pose) breaks the premise above: holding takes no new body, the search finds
      // the same pair at time 0 again, and the loop would never end. Drop the rest of the step.
      if (moving() == movingBefore) break;
    } else {
      // §2.1 step 4: respond with Newtonian impulses, then integrate on from the contact time.
      // Every search counts as an event, even when no pair still approaches at the contact time
      // (a box resting on the ground, which this technique cannot hold up): counting searches
      // is what bounds the loop.
      resolveCollisions(world, collisions, params.maxImpulsePasses, hooks);
      ++stats.events;
      ++eventsSinceHold;
    }
    remaining -= toi.tSeparated;
  }
  stats.contacts = static_cast<int>(findContacts(world, params.contactMargin).size());
  return stats;
}

}  // namespace boxsim
