/// \file
/// Bisection in time for the first collision of a step, with the restart on an earlier
/// collision with a third body that \thesis{§3.3.1} describes. Shared by every technique
/// that orders collisions chronologically (\thesis{§2.1}, \thesis{§3.3.1}, \thesis{§5.1}).
#pragma once

#include <utility>
#include <vector>

#include "boxsim/core/integrator.hpp"
#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/collision/separating_axis.hpp"
#include "boxsim/core/world.hpp"

namespace boxsim {

/// Tolerances of the time-of-impact search.
struct TimeOfImpactParams {
  /// s, > 0: the search stops when the bracket [tSeparated, tIntersecting] is narrower than
  /// this. 1e-5 s is 1/1667 of a 60 Hz frame, about 11 halvings; a body at 10 m/s then stops
  /// within 0.1 mm of its contact.
  double timeTolerance = 1e-5;
  /// m, >= 0: a pair "intersects" when its separating-axis depth exceeds this
  /// (kIntersectionDepthTolerance, which scene loading also rejects start overlaps by).
  double depthTolerance = kIntersectionDepthTolerance;
};

/// The bracket a search ends with.
struct TimeOfImpact {
  double tSeparated = 0.0;     ///< s after the start: no pair intersects
  double tIntersecting = 0.0;  ///< s after the start: the focus pair intersects
  std::pair<int, int> pair{-1, -1};  ///< the colliding pair the search ended focused on
  int bisections = 0;          ///< halvings, each one a roll-back and re-integration
  int restarts = 0;            ///< times an earlier collision with another body took over
};

/// Finds the first collision time after `start` (\thesis{§2.1}, \thesis{§3.3.1}).
/// Precondition: no pair intersects at `start`, and `firstPair` intersects after integrating
/// the whole `span` (s). Each bisection step restores `start`, integrates every body not
/// `held` (see integrateWorld) to the midpoint and tests the pairs: if the focus pair
/// intersects, the bracket closes from above; if it does not but another pair does, that
/// earlier collision becomes the focus (a restart); if none does, the bracket closes from below.
/// The search also stops when rounding no longer moves the midpoint. `extra` (empty, or one
/// wrench per body) holds forces besides gravity, constant over the span: contact forces of
/// the analytic method (analytic_lcp/analytic_stepper.hpp). Pairs `skip` skips (resting
/// contacts of the analytic method) are no collision to restart on.
/// \return the bracket; on return `world` holds the state at tSeparated.
TimeOfImpact findTimeOfImpact(World& world, const WorldState& start, double span,
                              std::pair<int, int> firstPair, Integrator integrator,
                              const TimeOfImpactParams& params = {},
                              const std::vector<char>& held = {},
                              const std::vector<Wrench>& extra = {},
                              const PairFilter& skip = {});

}  // namespace boxsim
