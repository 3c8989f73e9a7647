/// \file
/// A loop over independent items on several threads (OpenMP), for the damped step's threads
/// (ImpulseParams::threads), and the measure of the work such loops share (ParallelWork).
#pragma once

#include <array>
#include <chrono>
#include <cstddef>
#include <functional>

namespace boxsim {

/// Calls item(i) for i in [0, count), on up to `threads` threads (OpenMP, a static schedule:
/// thread t takes the t-th contiguous share); returns when every call has. The items must be
/// independent (each writes only its own results), so any order gives the same bits. Without
/// OpenMP (the WebAssembly build) the calls run in order on the calling thread.
void parallelFor(int count, int threads, const std::function<void(int)>& item);

/// The work of a step that threads share, for a model of what more cores would buy (Amdahl's
/// law with the loops' own granularity). Measured on any number of threads, one included: the
/// loops that would be shared are timed as they run. Three kinds, each of loops of independent
/// items: the narrow phases of the pairs with a fast body in a pass (one loop of `tests` items,
/// when ImpulseParams::parallelNarrowPhases are reached), COLLIDE's dependency levels (one loop
/// per level, when ImpulseParams::parallelContacts are reached; a pass with a sleeper beside an
/// awake body runs in order and is not counted), and the step's kept narrow phases, those of
/// its start and of FIXCONTACTCONSTRAINTS (KeptNarrowPhase::collideAll's rounds, when
/// ImpulseParams::parallelNarrowPhases are reached). N threads take
/// a loop of n items in ceil(n / N) rounds, so a kind's time on N threads, if every item cost
/// the same and the threads met for free, is its time on one times rounds[N] / rounds[1].
struct ParallelWork {
  using Clock = std::chrono::steady_clock;  ///< the clock the loops are timed with
  /// The thread counts the rounds are counted for.
  static constexpr std::array<int, 5> threadCounts = {1, 2, 8, 16, 64};
  /// Rounds per thread count (threadCounts[i]).
  using Rounds = std::array<long, threadCounts.size()>;
  double testSeconds = 0.0;   ///< s, in the shared loops of narrow phases
  double levelSeconds = 0.0;  ///< s, in COLLIDE's loops of the shared passes
  double keptSeconds = 0.0;   ///< s, in the rounds of the step's kept narrow phases
  Rounds testRounds{};        ///< rounds of the narrow phases
  Rounds levelRounds{};       ///< rounds of COLLIDE's levels
  Rounds keptRounds{};        ///< rounds of the step's kept narrow phases
  /// Counts a loop of n items into `rounds`.
  static void countLoop(Rounds& rounds, long n) {
    for (std::size_t i = 0; i < threadCounts.size(); ++i)
      rounds[i] += (n + threadCounts[i] - 1) / threadCounts[i];
  }
  /// When a loop measured into `work` starts: now, or (null: nothing measured) no clock read.
  static Clock::time_point startOf(const ParallelWork* work) {
    return work ? Clock::now() : Clock::time_point{};
  }
  /// Adds the time since `start` (startOf) to `seconds`.
  static void addSince(double& seconds, Clock::time_point start) {
    seconds += std::chrono::duration<double>(Clock::now() - start).count();
  }
};

/// item(i) for i in [0, count): a shared loop when there are at least `minItems` items
/// (ImpulseParams::parallelNarrowPhases), run by parallelFor on `threads` threads, else in
/// order on the calling thread. A shared loop's time and rounds are added to work->*seconds and
/// work->*rounds when `work` is given. Returns whether the loop ran on several threads.
bool sharedLoop(int count, int threads, int minItems, ParallelWork* work,
                double ParallelWork::*seconds, ParallelWork::Rounds ParallelWork::*rounds,
                const std::function<void(int)>& item);

/// The loop of a batch of kept narrow phases (KeptNarrowPhase::setLoop): each round a
/// sharedLoop measured into work->keptSeconds and keptRounds (`work` must outlive the loop).
std::function<void(int, const std::function<void(int)>&)> keptNarrowPhaseLoop(int threads,
                                                                             int minItems,
                                                                             ParallelWork* work);

}  // namespace boxsim
