#include "boxsim/io/simulate.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace boxsim {

std::map<std::string, std::string> runParameters(const Stepper& stepper, const World& world,
                                                 const std::string& scene, double dt,
                                                 double duration) {
  // The stepper's parameters go in first: map::insert never overwrites, so a key the stepper
  // sets itself, above all the "seed" of a technique that draws random numbers (§4.2), wins
  // over the defaults below.
  std::map<std::string, std::string> meta = stepper.parameters();
  meta.insert({{"method", stepper.name()},
               {"scene", scene},
               {"dt", shortestText(dt)},
               {"duration", shortestText(duration)},
               {"restitution", shortestText(world.restitution)},
               {"seed", "0"}});
  return meta;
}

long checkedStepCount(double dt, double duration, std::size_t bodyCount) {
  if (!std::isfinite(dt) || dt <= 0.0)
    throw std::invalid_argument("the time step dt must be a finite number > 0 s");
  if (!std::isfinite(duration) || duration < 0.0)
    throw std::invalid_argument("the duration must be a finite number >= 0 s");
  const double steps = std::round(duration / dt);
  if (steps > kMaxSteps || steps * static_cast<double>(bodyCount) > kMaxRecordedPoses)
    throw std::invalid_argument(
        "duration / dt asks for " + shortestText(steps) + " steps of " +
        std::to_string(bodyCount) + " bodies, more than the limit of " + shortestText(kMaxSteps) +
        " steps and " + shortestText(kMaxRecordedPoses) +
        " recorded poses; use a larger dt or a shorter duration");
  return static_cast<long>(steps);
}

namespace {
void requireFinite(const World& world, long step) {
  for (std::size_t i = 0; i < world.bodies.size(); ++i) {
    const BodyState& s = world.bodies[i].s;
    if (!s.x.allFinite() || !s.q.coeffs().allFinite() || !s.P.allFinite() || !s.L.allFinite())
      throw std::runtime_error("the state of body '" + world.names[i] +
                               "' is not finite after step " + std::to_string(step) +
                               "; the scene or time step is out of the method's range");
  }
}
}  // namespace

SimulateSummary simulate(World& world, Stepper& stepper, const SimulateOptions& options,
                         Recorder& recorder) {
  const long steps = checkedStepCount(options.dt, options.duration, world.bodies.size());
  SimulateSummary summary;
  world.applyLaunches(0.0);
  recorder.capture(world, 0.0);
  for (long k = 1; k <= steps; ++k) {
    // A body launched at time T starts moving with the step that begins at T.
    world.applyLaunches(static_cast<double>(k - 1) * options.dt + 1e-9 * options.dt);
    const StepStats stats = stepper.step(world, options.dt);
    requireFinite(world, k);
    recorder.capture(world, static_cast<double>(k) * options.dt, stats);
    ++summary.steps;
    summary.limitedSteps += stats.limitReached ? 1 : 0;
    summary.events += stats.events;
    summary.bisections += stats.bisections;
    if (options.progress) options.progress(static_cast<double>(k) / static_cast<double>(steps));
  }
  return summary;
}

}  // namespace boxsim
