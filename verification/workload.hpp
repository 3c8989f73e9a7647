// The share of their full workload the heaviest verification tests run (random stress seeds,
// steps of the chronological techniques in the determinism test). The environment variable
// BOXSIM_TEST_WORKLOAD, a number in (0, 1], sets it; unset, it is 1, the whole workload. The
// sanitize test preset (CMakePresets.json) sets it to 0.1: under AddressSanitizer and UBSan the
// same code paths run 25 to 45 times slower, and a tenth of the scenes still exercises every
// technique, while the Release suite keeps the full count.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace boxsim::testing {

/// BOXSIM_TEST_WORKLOAD as a number in (0, 1]; 1 when unset. Throws std::invalid_argument
/// naming the variable and the valid range for anything else (an empty string, text, 0, 2).
inline double testWorkload() {
  const char* text = std::getenv("BOXSIM_TEST_WORKLOAD");
  if (text == nullptr) return 1.0;
  char* end = nullptr;
  const double share = std::strtod(text, &end);
  if (end == text || *end != '\0' || !(share > 0.0 && share <= 1.0)) {
    throw std::invalid_argument("BOXSIM_TEST_WORKLOAD='" + std::string(text) +
                                "': expected a number in (0, 1], the share of the heaviest "
                                "tests' workload to run; unset it to run all of it");
  }
  return share;
}

/// `full` scaled by testWorkload(), rounded, and at least 1: a scaled test always runs.
inline long scaledCount(long full) {
  return std::max(1L, std::lround(static_cast<double>(full) * testWorkload()));
}

}  // namespace boxsim::testing
