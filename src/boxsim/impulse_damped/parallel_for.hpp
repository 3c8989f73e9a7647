/// \file
/// A loop over independent items on several threads (OpenMP), for the damped step's threads
/// (ImpulseParams::threads).
#pragma once

#include <functional>

namespace boxsim {

/// Calls item(i) for i in [0, count), on up to `threads` threads (OpenMP, a static schedule:
/// thread t takes the t-th contiguous share); returns when every call has. The items must be
/// independent (each writes only its own results), so any order gives the same bits. Without
/// OpenMP (the WebAssembly build) the calls run in order on the calling thread.
void parallelFor(int count, int threads, const std::function<void(int)>& item);

}  // namespace boxsim
