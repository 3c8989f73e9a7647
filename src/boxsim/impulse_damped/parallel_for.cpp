/// \file
/// parallelFor, the one place besides COLLIDE's levels (impulse_pass.cpp) that starts threads.
/// Compiled with OpenMP's flags alone (src/CMakeLists.txt), so the files that call it keep
/// their place in the unity batch.
#include "boxsim/impulse_damped/parallel_for.hpp"

#include "boxsim/impulse_damped/openmp.hpp"

namespace boxsim {

void parallelFor(int count, [[maybe_unused]] int threads, const std::function<void(int)>& item) {
  BOXSIM_OMP(omp parallel for num_threads(threads) schedule(static))
  for (int i = 0; i < count; ++i) item(i);
}

}  // namespace boxsim
