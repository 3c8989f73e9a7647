/// \file
/// An independent reference for the contact LCP: enumeration of the clamped set. Every subset
/// S of the contacts is tried, smallest first: f_S solves A_SS f_S = −b_S (minimum-norm least
/// squares), f is 0 elsewhere, and the first S whose f and a = A f + b satisfy the LCP
/// conditions within a tolerance is the answer. 2ⁿ subsets: for tests with n <= 12 only.
#pragma once

#include <optional>

#include "boxsim/analytic_lcp/lcp_solver.hpp"

namespace boxsim {

/// The forces f of the first clamped set (by size, then lexicographically) that solves the LCP
/// (A, b) with every condition violated by at most `tolerance` in lcpViolation's scaled units;
/// empty when no subset does. Throws std::invalid_argument for n > 16 (65 536 subsets) or
/// shapes that disagree.
std::optional<VecX> enumerateContactLcp(const MatX& A, const VecX& b, double tolerance = 1e-9);

}  // namespace boxsim
