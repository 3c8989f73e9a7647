/// \file
/// Runs a stepper over a world for a duration and records every step: the loop the command
/// line and every chapter driver share.
#pragma once

#include <functional>
#include <map>
#include <string>

#include "boxsim/core/stepper.hpp"
#include "boxsim/io/recorder.hpp"

namespace boxsim {

/// How long and how finely to run.
struct SimulateOptions {
  double dt = 1.0 / 60.0;  ///< time step, s, > 0
  double duration = 5.0;   ///< s, >= 0; the run takes round(duration / dt) steps
  /// Called after every step with the fraction done (0..1]; may be empty.
  std::function<void(double)> progress;
};

/// Totals of a run.
struct SimulateSummary {
  long steps = 0;          ///< steps taken
  long limitedSteps = 0;   ///< steps that hit a technique's work limit (StepStats::limitReached)
  long events = 0;         ///< collision events in all
  long bisections = 0;     ///< bisection steps in all
};

/// Most steps one run may take. Larger runs are refused before they start rather than failing
/// hours in.
inline constexpr double kMaxSteps = 1e7;
/// Most body poses (steps × bodies) one run may record: about 1 GB of frames.
inline constexpr double kMaxRecordedPoses = 2e7;

/// The header parameters of a run: the stepper's own parameters, then method, scene, dt,
/// duration, restitution and seed, every number in shortest round-trip text.
std::map<std::string, std::string> runParameters(const Stepper& stepper, const World& world,
                                                 const std::string& scene, double dt,
                                                 double duration);

/// Checks dt and duration before a run: finite, dt > 0, duration >= 0, and the step count and
/// recorded poses within kMaxSteps and kMaxRecordedPoses. Throws std::invalid_argument naming
/// the problem and the fix.
long checkedStepCount(double dt, double duration, std::size_t bodyCount);

/// Records the initial frame, then steps `stepper` round(duration / dt) times, recording a
/// frame after each (frame k at t = k dt, computed from k so that time does not drift).
/// Bodies waiting in world.launches are launched at the start of the step that begins at (or
/// just after) their time.
/// Throws std::invalid_argument as checkedStepCount() does, and std::runtime_error naming the
/// step and the body when a body's state stops being finite.
SimulateSummary simulate(World& world, Stepper& stepper, const SimulateOptions& options,
                         Recorder& recorder);

}  // namespace boxsim
