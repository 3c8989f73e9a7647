/// \file
/// The basic colliding technique (\thesis{§2.1}, \thesis{§3.3.1}): integrate every body
/// forward; when a pair intersects, bisect in time for the first contact, roll every body back
/// to it, apply the Newtonian impulse, and go on with the rest of the step.
///
/// It handles collisions only, never resting contact: as a box settles its bounces shrink
/// geometrically (height ratio e² per bounce) and so do the intervals between them, so the
/// collisions crowd together without bound (the chattering of \thesis{§4.3}); a body resting
/// on another collides again the instant gravity pulls it in, and time cannot advance at all.
/// BasicCollidingParams::maxEventsPerStep bounds the work of one step instead of hanging.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "boxsim/basic_colliding/time_of_impact.hpp"
#include "boxsim/core/integrator.hpp"
#include "boxsim/core/stepper.hpp"

namespace boxsim {

/// Parameters of the basic colliding technique.
struct BasicCollidingParams {
  /// Integration scheme between collisions.
  /// DEVIATION(\thesis{§6.2}): the thesis integrated with forward Euler; here semi-implicit
  /// Euler is the default. Forward Euler adds \f$g^2\Delta t^2/2\f$ of energy per unit mass
  /// every step in free flight, about \f$g\,\Delta t\sqrt{2gh}\f$ per bounce of height h,
  /// while restitution removes \f$(1 - e^2)\,g h\f$. The two balance at
  /// \f[ h^* = \frac{2 g \Delta t^2}{(1 - e^2)^2}, \f]
  /// 0.15 m at 60 Hz with e = 0.9: under forward Euler a dropped box never comes to rest but keeps bouncing that high
  /// (figure s2_1_die_height_energy shows both). ForwardEuler stays selectable.
  Integrator integrator = Integrator::SemiImplicitEuler;
  /// Bisection tolerances (\thesis{§3.3.1}).
  TimeOfImpactParams timeOfImpact;
  /// Collision events (time-of-impact searches, each followed by the impulses of that instant)
  /// one step may resolve. When a step needs more (a box chattering to rest, \thesis{§4.3}),
  /// the rest of that step is dropped: bodies keep the last collision-free
  /// state and velocities, StepStats::limitReached is set, and the run goes on. 100 events in a
  /// 1/60 s frame is a collision every 0.17 ms, far past anything visible.
  int maxEventsPerStep = 100;
  /// Passes over the pairs colliding at one instant: each pass applies an impulse to every
  /// pair still approaching, until none is (simultaneous collisions, a box on a stack).
  int maxImpulsePasses = 32;
  /// m: pairs closer than this at the end of a step count as contacts in StepStats.
  double contactMargin = 1e-3;
};

/// One pair colliding at the first overlapping state of a time-of-impact search, with its
/// impulse points.
struct PairCollision {
  int a = -1;                    ///< body index
  int b = -1;                    ///< body index
  Vec3 normal = Vec3::UnitY();   ///< unit, from a to b
  /// m: the manifold centroid (\alg{COLLIDE L7}), or every manifold point
  /// (CollisionLoopHooks::simultaneousImpulses).
  std::vector<Vec3> points;
  /// e of each point, fixed by its approach speed before the first impulse pass.
  std::vector<double> restitution;
};

/// What the analytic method (\thesis{§3.3.1}) adds to the loop of the basic colliding
/// technique; every member may be empty, which is the basic technique itself.
struct CollisionLoopHooks {
  /// Forces besides gravity over the interval that starts at `world`'s current state, one
  /// wrench per body (or empty for none); held constant over the interval, as Euler
  /// integration treats forces (\thesis{§6.2}). Called once per integration interval.
  std::function<std::vector<Wrench>(const World& world)> extraForces;
  /// The restitution of a collision whose bodies approach at `speed` m/s at the contact
  /// (sticky collisions, \thesis{§4.3}); empty: world.restitution for every collision.
  std::function<double(const World& world, double speed)> restitution;
  /// Intersecting pairs that are no collision (resting contacts held by forces, whose small
  /// overlap the forces mend); empty: every intersecting pair is a collision.
  PairFilter notColliding;
  /// Empty: one impulse point per colliding pair, the manifold centroid (\alg{COLLIDE L7}), as the
  /// basic technique does. Set: every manifold point is a collision point (Baraff's point
  /// contacts), so a rocking box whose corner hits while its centroid does not still gets an
  /// impulse, and this applies the impulses of all of a pair's points at once, returning how
  /// many were nonzero (the analytic method solves their velocity LCP).
  std::function<int(World& world, const PairCollision& collision)> simultaneousImpulses;
};

/// One step of dt s of the \thesis{§2.1} loop, repeated until dt is covered: integrate every
/// body (with the hooks' extra forces), find the first intersecting pair, bisect for its time of
/// impact, roll back, apply Newtonian impulses to the pairs intersecting then (in passes until
/// none approaches; restitution from the hooks), and go on. Bounded by
/// params.maxEventsPerStep as BasicCollidingParams describes.
StepStats advanceColliding(World& world, double dt, const BasicCollidingParams& params,
                           const CollisionLoopHooks& hooks = {});

/// The work limit of advanceColliding() in words (Stepper::workLimit()): the bound of
/// params.maxEventsPerStep collision events a step, which collisions crowding together as
/// bodies come to rest meet (\thesis{§4.3}).
std::string collisionLoopWorkLimit(const BasicCollidingParams& params);

/// The basic colliding technique as a Stepper ("basic_colliding").
class BasicCollidingStepper final : public Stepper {
 public:
  /// A stepper with the given parameters. Throws std::invalid_argument when timeTolerance is
  /// not > 0, depthTolerance is negative, or maxEventsPerStep or maxImpulsePasses is < 1.
  explicit BasicCollidingStepper(const BasicCollidingParams& params = {});
  std::string name() const override { return "basic_colliding"; }
  std::map<std::string, std::string> parameters() const override;
  std::string workLimit() const override { return collisionLoopWorkLimit(params_); }
  /// Advances by dt (s): \thesis{§2.1} steps 1-4, repeated until the whole dt is covered
  /// (advanceColliding with no hooks).
  StepStats step(World& world, double dt) override;
  /// The parameters it runs with.
  const BasicCollidingParams& params() const { return params_; }

 private:
  BasicCollidingParams params_;
};

/// Throws std::invalid_argument naming `method` when the loop parameters are out of range
/// (timeTolerance not > 0, depthTolerance negative, an iteration bound < 1).
void requireCollisionLoopParams(const BasicCollidingParams& params, const std::string& method);

}  // namespace boxsim
