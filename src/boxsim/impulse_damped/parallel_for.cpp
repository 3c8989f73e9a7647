/// \file
/// parallelFor, the one place besides COLLIDE's levels (impulse_pass.cpp) that starts threads,
/// and the loop of the kept narrow phases that runs on it.
/// Compiled with OpenMP's flags alone (src/CMakeLists.txt), so the files that call it keep
/// their place in the unity batch.
#include "boxsim/impulse_damped/parallel_for.hpp"

#include "boxsim/impulse_damped/openmp.hpp"

namespace boxsim {

void parallelFor(int count, [[maybe_unused]] int threads, const std::function<void(int)>& item) {
  BOXSIM_OMP(omp parallel for num_threads(threads) schedule(static))
  for (int i = 0; i < count; ++i) item(i);
}

bool sharedLoop(int count, int threads, int minItems, ParallelWork* work,
                double ParallelWork::*seconds, ParallelWork::Rounds ParallelWork::*rounds,
                const std::function<void(int)>& item) {
  const bool shared = count > 0 && count >= minItems;
  const auto start = ParallelWork::startOf(shared ? work : nullptr);
  const bool threaded = threads > 1 && shared;
  if (threaded) {
    parallelFor(count, threads, item);
  } else {
    for (int i = 0; i < count; ++i) item(i);
  }
  if (work && shared) {
    ParallelWork::addSince(work->*seconds, start);
    ParallelWork::countLoop(work->*rounds, count);
  }
  return threaded;
}

std::function<void(int, const std::function<void(int)>&)> keptNarrowPhaseLoop(int threads,
                                                                             int minItems,
                                                                             ParallelWork* work) {
  return [threads, minItems, work](int count, const std::function<void(int)>& item) {
    sharedLoop(count, threads, minItems, work, &ParallelWork::keptSeconds,
               &ParallelWork::keptRounds, item);
  };
}

}  // namespace boxsim
