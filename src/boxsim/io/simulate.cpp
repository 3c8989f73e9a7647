#include "boxsim/io/simulate.hpp"

#include <cmath>
#include <cstdio>
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

namespace {

/// Up to 12 significant digits: what a user types back (within kWholeStepTolerance).
std::string roundedText(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.12g", value);
  return buffer;
}

/// The refusal of a duration that is `steps` (not whole) steps of dt, with the nearest
/// durations that are whole steps and time steps that divide the duration.
std::invalid_argument notWholeSteps(double dt, double duration, double steps) {
  const double below = std::floor(steps);
  const double above = std::ceil(steps);
  std::string durations = roundedText(above * dt) + " s";
  std::string timeSteps = roundedText(duration / above) + " s";
  if (below >= 1.0) {
    durations = roundedText(below * dt) + " s or " + durations;
    timeSteps += " or " + roundedText(duration / below) + " s";
  }
  return std::invalid_argument(
      "the duration " + shortestText(duration) + " s is " + roundedText(steps) +
      " steps of dt = " + shortestText(dt) +
      " s; a run takes whole steps, so that it ends at the duration asked for: use a duration "
      "of " + durations + ", or a dt that divides " + shortestText(duration) + " s, such as " +
      timeSteps);
}

}  // namespace

long checkedStepCount(double dt, double duration) {
  if (!std::isfinite(dt) || dt <= 0.0)
    throw std::invalid_argument("the time step dt must be a finite number > 0 s");
  if (!std::isfinite(duration) || duration < 0.0)
    throw std::invalid_argument("the duration must be a finite number >= 0 s");
  const double exact = duration / dt;
  const double steps = std::round(exact);
  if (steps > kMaxSteps)
    throw std::invalid_argument("duration / dt asks for " + shortestText(steps) +
                                " steps, more than the limit of " + shortestText(kMaxSteps) +
                                "; use a larger dt or a shorter duration");
  if (std::abs(exact - steps) > kWholeStepTolerance * steps)
    throw notWholeSteps(dt, duration, exact);
  return static_cast<long>(steps);
}

void checkRecordedPoses(long steps, std::size_t bodyCount) {
  const double poses = static_cast<double>(steps) * static_cast<double>(bodyCount);
  if (poses > kMaxRecordedPoses)
    throw std::invalid_argument(
        std::to_string(steps) + " steps of " + std::to_string(bodyCount) +
        " bodies are more than the limit of " + shortestText(kMaxRecordedPoses) +
        " poses kept in memory; use a larger dt or a shorter duration, or pass the frames to a "
        "FrameSink");
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

void requireFrictionModel(const World& world, const Stepper& stepper) {
  if (stepper.modelsFriction()) return;
  for (std::size_t i = 0; i < world.bodies.size(); ++i)
    if (!world.bodies[i].friction.frictionless())
      throw std::invalid_argument(
          "body '" + world.names[i] + "' has Coulomb friction, which the method '" + stepper.name() +
          "' does not model (the thesis' techniques are frictionless). Fix: run it with "
          "--method damped or --method impulse, or remove \"friction\" from the scene");
}

SimulateSummary simulate(World& world, Stepper& stepper, const SimulateOptions& options,
                         Recorder& recorder) {
  const long steps = checkedStepCount(options.dt, options.duration);
  requireFrictionModel(world, stepper);
  if (recorder.keepsFrames()) checkRecordedPoses(steps, world.bodies.size());
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
