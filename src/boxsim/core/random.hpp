/// \file
/// The seeded random numbers of boxsim (visual plausibility, \thesis{§4.2}; the spins of the
/// clump builder): the 32-bit Mersenne Twister MT19937 of the C++ standard library, whose
/// output for a seed the standard fixes, so a seed gives the same numbers on every platform
/// and compiler, WebAssembly included. Uniform numbers are drawn as GSL draws them from its
/// gsl_rng_mt19937 (output / 2³²), and seed 0 means GSL's default seed 4357: the streams of
/// the GSL generator boxsim used before, number for number.
#pragma once

#include <cstdint>
#include <random>

namespace boxsim {

/// A seeded stream of uniform numbers in [0, 1). Copying copies the state, so a copy continues
/// the same stream.
class UniformRandom {
 public:
  /// The stream of `seed`: of 4357 for 0, otherwise of its low 32 bits (as GSL takes it).
  explicit UniformRandom(unsigned long long seed)
      : generator_(static_cast<std::uint32_t>(seed == 0 ? 4357 : seed & 0xffffffffULL)) {}
  /// The next number, k / 2³² for the generator's next 32-bit output k: in [0, 1), a multiple
  /// of 2⁻³².
  double next() { return static_cast<double>(generator_()) / 4294967296.0; }

 private:
  std::mt19937 generator_;
};

}  // namespace boxsim
