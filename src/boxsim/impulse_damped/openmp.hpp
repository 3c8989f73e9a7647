/// \file
/// OpenMP where the build has it: the techniques' threads (ImpulseParams::threads).
#pragma once

/// An OpenMP pragma where the build has OpenMP (-fopenmp), nothing elsewhere (the WebAssembly
/// build): the loop then runs on one thread, with the same result.
#if defined(_OPENMP)
#define BOXSIM_OMP(directive) _Pragma(#directive)
#else
#define BOXSIM_OMP(directive)
#endif
