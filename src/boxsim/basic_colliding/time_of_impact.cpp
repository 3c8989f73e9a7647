/// \file
/// The bisection search for the time of impact (\thesis{§2.1}, \thesis{§3.3.1}).
#include "boxsim/basic_colliding/time_of_impact.hpp"

#include "boxsim/collision/broad_phase.hpp"

namespace boxsim {

TimeOfImpact findTimeOfImpact(World& world, const WorldState& start, double span,
                              std::pair<int, int> firstPair, Integrator integrator,
                              const TimeOfImpactParams& params, const std::vector<char>& held,
                              const std::vector<Wrench>& extra, const PairFilter& skip) {
  const auto advanceTo = [&](double t) {
    world.restoreState(start);
    integrateWorld(world, t, integrator, held, extra);
  };
  TimeOfImpact toi;
  toi.pair = firstPair;
  toi.tSeparated = 0.0;
  toi.tIntersecting = span;
  while (toi.tIntersecting - toi.tSeparated > params.timeTolerance) {
    const double mid = 0.5 * (toi.tSeparated + toi.tIntersecting);
    if (mid <= toi.tSeparated || mid >= toi.tIntersecting) break;  // rounding: cannot halve
    advanceTo(mid);
    ++toi.bisections;
    if (pairIntersects(world, toi.pair.first, toi.pair.second, params.depthTolerance)) {
      toi.tIntersecting = mid;
      continue;
    }
    const std::pair<int, int> other =
        firstIntersectingPair(world, params.depthTolerance, skip);
    if (other.first >= 0) {
      // §3.3.1: the search uncovered a collision with a third body before the one it was
      // refining; discard the current one and restart the search on the earlier collision.
      toi.pair = other;
      toi.tIntersecting = mid;
      ++toi.restarts;
    } else {
      toi.tSeparated = mid;
    }
  }
  advanceTo(toi.tSeparated);
  return toi;
}

}  // namespace boxsim
