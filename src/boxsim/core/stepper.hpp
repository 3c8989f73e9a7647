/// \file
/// The one interface every technique implements, so that any scene runs under any technique
/// and the same recorder and metrics compare them.
#pragma once

#include <map>
#include <string>

#include "boxsim/core/world.hpp"

namespace boxsim {

/// What one step did, for the recorder and for comparing techniques.
struct StepStats {
  int events = 0;      ///< collision events resolved (for chronological techniques: collision times found)
  int bisections = 0;  ///< bisection steps of time-of-impact searches (each one a roll-back)
  int restarts = 0;    ///< searches restarted on an earlier collision with a third body
  int contacts = 0;    ///< contact manifolds touching at the end of the step
  /// Bodies asleep at the end of the step (computational stability, \thesis{§4.5}); 0 for
  /// techniques that do not sleep bodies.
  int sleeping = 0;
  /// True when the step hit a documented work limit (e.g. the basic colliding technique's
  /// events-per-step bound) and did less than the technique asks for.
  bool limitReached = false;
  /// Single-body integrations (one body advanced over one interval, roll-back searches
  /// included): the work \thesis{§2.4.3}'s timewarp saves by rewinding only bodies near an
  /// event. Counted by the chronological techniques (basic colliding, analytic, timewarp).
  long bodyIntegrations = 0;
  /// Single-body roll-backs: a body's state reset to an earlier one to be integrated again.
  long bodyRollbacks = 0;
  /// Collision and contact passes run (impulse-based techniques, \alg{DAMPEDINTEGRATION L1-L2}).
  int passes = 0;

  /// Accumulates the counts of another step; `contacts` and `sleeping` take the later value.
  StepStats& operator+=(const StepStats& o) {
    events += o.events;
    bisections += o.bisections;
    restarts += o.restarts;
    contacts = o.contacts;
    sleeping = o.sleeping;
    limitReached = limitReached || o.limitReached;
    bodyIntegrations += o.bodyIntegrations;
    bodyRollbacks += o.bodyRollbacks;
    passes += o.passes;
    return *this;
  }
};

/// A technique that advances a world by one time step.
class Stepper {
 public:
  virtual ~Stepper() = default;
  /// The method name used on the command line and in output headers.
  virtual std::string name() const = 0;
  /// The technique's parameters as text, for the header of every output file
  /// (name -> value, e.g. "integrator" -> "semi_implicit_euler").
  virtual std::map<std::string, std::string> parameters() const { return {}; }
  /// The work limit behind StepStats::limitReached, in words for a warning: the bound and what
  /// makes a run meet it. Empty for a technique without one.
  virtual std::string workLimit() const { return {}; }
  /// Whether the technique models the Coulomb friction of RigidBody::friction. The thesis'
  /// techniques are frictionless (\thesis{§3.3.2}); impulse and damped integration add it
  /// (core/newtonian_impulse.hpp, applyPatchFriction). A driver refuses a world with friction
  /// under a technique that would ignore it (requireFrictionModel in io/simulate.hpp).
  virtual bool modelsFriction() const { return false; }
  /// Advances `world` by dt seconds (dt > 0) and reports what it did.
  virtual StepStats step(World& world, double dt) = 0;
};

}  // namespace boxsim
