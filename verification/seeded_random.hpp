// Seeded random numbers for the verification tests: GSL's mt19937, which gives the same
// numbers on every platform, so a randomized test checks the same cases on every run.
#pragma once

#include <gsl/gsl_randist.h>
#include <gsl/gsl_rng.h>

#include <cmath>
#include <vector>

#include "boxsim/core/math.hpp"

namespace boxsim::testing {

/// A seeded GSL mt19937 generator, freed on scope exit.
class SeededRandom {
 public:
  explicit SeededRandom(unsigned long seed) : r_(gsl_rng_alloc(gsl_rng_mt19937)) {
    gsl_rng_set(r_, seed);
  }
  ~SeededRandom() { gsl_rng_free(r_); }
  SeededRandom(const SeededRandom&) = delete;
  SeededRandom& operator=(const SeededRandom&) = delete;

  /// Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * gsl_rng_uniform(r_); }
  /// Uniform whole number in [lo, hi].
  int integer(int lo, int hi) {
    return lo + static_cast<int>(gsl_rng_uniform_int(r_, static_cast<unsigned long>(hi - lo + 1)));
  }
  /// A multiple of `step` in [lo, hi]: snapped values make bounds touch and sort keys tie.
  double snapped(double lo, double hi, double step) {
    return lo + step * integer(0, static_cast<int>((hi - lo) / step));
  }
  /// Each component uniform in [lo, hi).
  Vec3 vector(double lo, double hi) { return Vec3(uniform(lo, hi), uniform(lo, hi), uniform(lo, hi)); }
  /// A uniformly distributed rotation (Shoemake's subgroup algorithm).
  Quat rotation() {
    const double u1 = uniform(0, 1), u2 = uniform(0, 2 * kPi), u3 = uniform(0, 2 * kPi);
    const Quat q(std::sqrt(u1) * std::cos(u3), std::sqrt(1 - u1) * std::sin(u2),
                 std::sqrt(1 - u1) * std::cos(u2), std::sqrt(u1) * std::sin(u3));
    return q.normalized();
  }
  /// Shuffles `values` in place.
  void shuffle(std::vector<int>& values) {
    gsl_ran_shuffle(r_, values.data(), values.size(), sizeof(int));
  }

 private:
  gsl_rng* r_;
};

}  // namespace boxsim::testing
