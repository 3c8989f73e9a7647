/// \file
/// The basic colliding technique (\thesis{§2.1}, \thesis{§3.3.1}): integrate every body
/// forward; when a pair intersects, bisect in time for the first contact, roll every body back
/// to it, apply the Newtonian impulse, and go on with the rest of the step.
///
/// It handles collisions only, never resting contact: as a box comes to rest its bounces
/// shrink geometrically (height ratio e² per bounce) and so do the intervals between them, so
/// the number of collisions per second grows without bound (the chattering of \thesis{§4.3}).
/// BasicCollidingParams::maxEventsPerStep bounds the work of one step instead of hanging.
#pragma once

#include "boxsim/basic_colliding/time_of_impact.hpp"
#include "boxsim/core/integrator.hpp"
#include "boxsim/core/stepper.hpp"

namespace boxsim {

/// Parameters of the basic colliding technique.
struct BasicCollidingParams {
  /// Integration scheme between collisions.
  /// DEVIATION(\thesis{§6.2}): the thesis integrated with forward Euler; here semi-implicit
  /// Euler is the default. Forward Euler adds g²Δt²/2 of energy per unit mass every step in
  /// free flight, about g Δt √(2 g h) per bounce of height h, while restitution removes
  /// (1 - e²) g h. The two balance at h* = 2 g Δt² / (1 - e²)², 0.15 m at 60 Hz with e = 0.9:
  /// under forward Euler a dropped box never comes to rest but keeps bouncing that high
  /// (figure s2_1_die_height_energy shows both). ForwardEuler stays selectable.
  Integrator integrator = Integrator::SemiImplicitEuler;
  /// Bisection tolerances (\thesis{§3.3.1}: "within some small epsilon").
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

/// The basic colliding technique as a Stepper ("basic_colliding").
class BasicCollidingStepper final : public Stepper {
 public:
  /// A stepper with the given parameters.
  explicit BasicCollidingStepper(const BasicCollidingParams& params = {}) : params_(params) {}
  std::string name() const override { return "basic_colliding"; }
  std::map<std::string, std::string> parameters() const override;
  /// Advances by dt (s): \thesis{§2.1} steps 1-4, repeated until the whole dt is covered.
  StepStats step(World& world, double dt) override;
  /// The parameters it runs with.
  const BasicCollidingParams& params() const { return params_; }

 private:
  /// Applies Newtonian impulses (restitution world.restitution) to every pair that intersects
  /// in `atImpact` and approaches in `world`; returns the number of impulses applied.
  int resolveCollisions(World& world, const World& atImpact) const;

  BasicCollidingParams params_;
};

}  // namespace boxsim
