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
  double duration = 5.0;   ///< s, >= 0, a whole number of steps (checkedStepCount())
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
/// Most body poses (steps × bodies) one run may keep in memory (a Recorder without a sink):
/// about 1 GB of frames. A run streamed to a FrameSink has no such limit.
inline constexpr double kMaxRecordedPoses = 2e7;
/// How close duration / dt must come to a whole number n of steps, relative to n: 1e-9. Decimal
/// input rounds duration and dt by about 1e-16 each, so a duration meant as n steps passes with
/// a wide margin, while n dt and the duration asked for agree to 1 part in 10⁹.
inline constexpr double kWholeStepTolerance = 1e-9;

/// The header parameters of a run: the stepper's own parameters, then method, scene, dt,
/// duration, restitution and seed, every number in shortest round-trip text.
std::map<std::string, std::string> runParameters(const Stepper& stepper, const World& world,
                                                 const std::string& scene, double dt,
                                                 double duration);

/// The step count n of a run, checked before it starts: dt and duration finite, dt > 0,
/// duration >= 0, duration a whole number of steps (|duration / dt − n| <= kWholeStepTolerance
/// n, so that the run ends at the duration asked for, every step dt long), and n within
/// kMaxSteps. Throws std::invalid_argument naming the problem and the fix: for a duration that
/// is no whole number of steps, the nearest durations that are and time steps that divide it.
long checkedStepCount(double dt, double duration);

/// Checks that `steps` steps of `bodyCount` bodies stay within kMaxRecordedPoses, for a recorder
/// that keeps its frames in memory. Throws std::invalid_argument naming the limit and the fix.
void checkRecordedPoses(long steps, std::size_t bodyCount);

/// Refuses a world with Coulomb friction (RigidBody::friction) under a technique that would
/// ignore it (Stepper::modelsFriction): throws std::invalid_argument naming the first such body
/// (by world.names), the method, and the fix (a method that models friction, or no friction).
void requireFrictionModel(const World& world, const Stepper& stepper);

/// Records the initial frame, then steps `stepper` n = checkedStepCount() times, recording a
/// frame after each (frame k at t = k dt, computed from k so that time does not drift).
/// Bodies waiting in world.launches are launched at the start of the step that begins at (or
/// just after) their time.
/// Throws std::invalid_argument as checkedStepCount() does (and checkRecordedPoses() when the
/// recorder keeps its frames, requireFrictionModel() for friction the method ignores), and std::runtime_error naming the step and the body when a
/// body's state stops being finite.
SimulateSummary simulate(World& world, Stepper& stepper, const SimulateOptions& options,
                         Recorder& recorder);

}  // namespace boxsim
