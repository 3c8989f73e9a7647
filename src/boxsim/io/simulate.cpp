#include "boxsim/io/simulate.hpp"

#include <cmath>
#include <stdexcept>

namespace boxsim {

SimulateSummary simulate(World& world, Stepper& stepper, const SimulateOptions& options,
                         Recorder& recorder) {
  if (!std::isfinite(options.dt) || options.dt <= 0.0)
    throw std::invalid_argument("the time step dt must be a finite number > 0 s");
  if (!std::isfinite(options.duration) || options.duration < 0.0)
    throw std::invalid_argument("the duration must be a finite number >= 0 s");
  const long steps = std::lround(options.duration / options.dt);
  SimulateSummary summary;
  recorder.capture(world, 0.0);
  for (long k = 1; k <= steps; ++k) {
    const StepStats stats = stepper.step(world, options.dt);
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
