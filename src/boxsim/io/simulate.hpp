/// \file
/// Runs a stepper over a world for a duration and records every step: the loop the command
/// line and every chapter driver share.
#pragma once

#include <functional>

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

/// Records the initial frame, then steps `stepper` round(duration / dt) times, recording a
/// frame after each (frame k at t = k dt, computed from k so that time does not drift).
/// Throws std::invalid_argument when dt or duration is not finite or out of range.
SimulateSummary simulate(World& world, Stepper& stepper, const SimulateOptions& options,
                         Recorder& recorder);

}  // namespace boxsim
