/// \file
/// Enumeration of the clamped set: the reference the pivoting solver is tested against.
#include "boxsim/analytic_lcp/lcp_enumeration.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <bit>
#include <stdexcept>
#include <vector>

namespace boxsim {

std::optional<VecX> enumerateContactLcp(const MatX& A, const VecX& b, double tolerance) {
  const int n = static_cast<int>(b.size());
  if (n > 16) throw std::invalid_argument("contact LCP enumeration: at most 16 contacts");
  if (A.rows() != n || A.cols() != n)
    throw std::invalid_argument("contact LCP enumeration: A must be n x n with b of size n");
  // Subsets by size, then by bit pattern: the same order on every run.
  std::vector<unsigned> subsets(1u << n);
  for (unsigned s = 0; s < subsets.size(); ++s) subsets[s] = s;
  std::stable_sort(subsets.begin(), subsets.end(),
                   [](unsigned l, unsigned r) { return std::popcount(l) < std::popcount(r); });
  for (const unsigned s : subsets) {
    std::vector<int> clamped;
    for (int i = 0; i < n; ++i)
      if (s & (1u << i)) clamped.push_back(i);
    VecX f = VecX::Zero(n);
    if (!clamped.empty()) {
      const int m = static_cast<int>(clamped.size());
      MatX Ass(m, m);
      VecX rhs(m);
      for (int r = 0; r < m; ++r) {
        for (int c = 0; c < m; ++c) Ass(r, c) = A(clamped[r], clamped[c]);
        rhs[r] = -b[clamped[r]];
      }
      const VecX x = Ass.completeOrthogonalDecomposition().solve(rhs);
      for (int r = 0; r < m; ++r) f[clamped[r]] = x[r];
    }
    if (lcpViolation(A, b, f) <= tolerance) return f;
  }
  return std::nullopt;
}

}  // namespace boxsim
