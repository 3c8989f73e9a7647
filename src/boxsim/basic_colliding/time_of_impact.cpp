#include "boxsim/basic_colliding/time_of_impact.hpp"

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/collision/separating_axis.hpp"

namespace boxsim {

bool pairIntersects(const World& world, int i, int j, double depthTolerance) {
  const SeparatingAxisResult sat =
      separatingAxisTest(Obb::of(world.bodies[i]), Obb::of(world.bodies[j]));
  return sat.intersecting && sat.depth > depthTolerance;
}

std::pair<int, int> firstIntersectingPair(const World& world, double depthTolerance) {
  for (const std::pair<int, int>& p : candidatePairs(world))
    if (pairIntersects(world, p.first, p.second, depthTolerance)) return p;
  return {-1, -1};
}

namespace {
void advanceFrom(World& world, const WorldState& start, double t, Integrator integrator) {
  world.restoreState(start);
  integrateWorld(world, t, integrator);
}
}  // namespace

TimeOfImpact findTimeOfImpact(World& world, const WorldState& start, double span,
                              std::pair<int, int> firstPair, Integrator integrator,
                              const TimeOfImpactParams& params) {
  TimeOfImpact toi;
  toi.pair = firstPair;
  toi.tSeparated = 0.0;
  toi.tIntersecting = span;
  while (toi.tIntersecting - toi.tSeparated > params.timeTolerance) {
    const double mid = 0.5 * (toi.tSeparated + toi.tIntersecting);
    advanceFrom(world, start, mid, integrator);
    ++toi.bisections;
    if (pairIntersects(world, toi.pair.first, toi.pair.second, params.depthTolerance)) {
      toi.tIntersecting = mid;
      continue;
    }
    const std::pair<int, int> other = firstIntersectingPair(world, params.depthTolerance);
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
  advanceFrom(world, start, toi.tSeparated, integrator);
  return toi;
}

}  // namespace boxsim
