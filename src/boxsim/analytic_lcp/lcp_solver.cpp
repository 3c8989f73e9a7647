/// \file
/// Baraff's pivoting method for the contact LCP (Baraff 1994, §4–5; \thesis{§3.3.1}).
#include "boxsim/analytic_lcp/lcp_solver.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace boxsim {

namespace {

/// Where a contact stands in Baraff's method: not yet driven, clamped (a = 0, f >= 0), or
/// not clamped (f = 0, a >= 0).
enum class ContactSet : unsigned char { Undriven, Clamped, NotClamped };

/// fdirection(d) of Baraff 1994, §5: the change of the forces that moves a_d while every
/// clamped contact keeps a = 0 and every other force stays put: Δf_d = 1, Δf_C solves
/// A_CC Δf_C = −A_Cd, the rest is 0.
VecX forceDirection(const MatX& A, const std::vector<ContactSet>& set, int d,
                    LcpLinearSolver solver) {
  const int n = static_cast<int>(A.rows());
  VecX df = VecX::Zero(n);
  df[d] = 1.0;
  std::vector<int> clamped;
  for (int i = 0; i < n; ++i)
    if (set[i] == ContactSet::Clamped) clamped.push_back(i);
  if (clamped.empty()) return df;
  const int m = static_cast<int>(clamped.size());
  MatX Acc(m, m);
  VecX rhs(m);
  for (int r = 0; r < m; ++r) {
    for (int c = 0; c < m; ++c) Acc(r, c) = A(clamped[r], clamped[c]);
    rhs[r] = -A(clamped[r], d);
  }
  // DEVIATION(Baraff 1994 §5, "A11 x = -v1"): Baraff assumes A_CC nonsingular. Redundant
  // contacts (four coplanar corners on a plane) make it singular; the minimum-norm
  // least-squares solution then still keeps the clamped accelerations at zero when the system
  // is consistent, and spreads the load evenly among the redundant contacts.
  const VecX x = solver == LcpLinearSolver::Ldlt ? VecX(Acc.ldlt().solve(rhs))
                                                 : VecX(Acc.completeOrthogonalDecomposition().solve(rhs));
  for (int r = 0; r < m; ++r) df[clamped[r]] = x[r];
  return df;
}

/// maxstep(f, a, Δf, Δa, d) of Baraff 1994, §5: the largest s >= 0 for which f + s Δf and
/// a + s Δa keep the conditions of every set, and the contact j whose condition stops it
/// (j = d: a_d reaches 0). j = -1 when nothing bounds the step.
std::pair<double, int> maxStep(const VecX& f, const VecX& a, const VecX& df, const VecX& da,
                               const std::vector<ContactSet>& set, int d) {
  double s = std::numeric_limits<double>::infinity();
  int j = -1;
  if (da[d] > 0.0) {
    s = -a[d] / da[d];
    j = d;
  }
  for (int i = 0; i < static_cast<int>(f.size()); ++i) {
    if (set[i] == ContactSet::Clamped && df[i] < 0.0) {
      const double si = -f[i] / df[i];
      if (si < s) {
        s = si;
        j = i;
      }
    } else if (set[i] == ContactSet::NotClamped && da[i] < 0.0) {
      const double si = -a[i] / da[i];
      if (si < s) {
        s = si;
        j = i;
      }
    }
  }
  return {std::max(s, 0.0), j};
}

void requireProblem(const MatX& A, const VecX& b) {
  if (A.rows() != A.cols() || A.rows() != b.size())
    throw std::invalid_argument("contact LCP: A must be n x n and b of size n (got " +
                                std::to_string(A.rows()) + " x " + std::to_string(A.cols()) +
                                " and " + std::to_string(b.size()) + ")");
  if (!A.allFinite() || !b.allFinite())
    throw std::invalid_argument("contact LCP: A and b must be finite");
}

}  // namespace

LcpResult solveContactLcp(const MatX& A, const VecX& b, const LcpParams& params) {
  requireProblem(A, b);
  const int n = static_cast<int>(b.size());
  LcpResult result;
  result.f = VecX::Zero(n);
  result.a = b;
  std::vector<ContactSet> set(n, ContactSet::Undriven);
  const long maxPivots = static_cast<long>(params.maxPivotsPerContact) * std::max(n, 1);
  VecX& f = result.f;
  VecX& a = result.a;
  // compute_forces: while an undriven contact accelerates into its partner faster than ε
  // (\thesis{§3.3.1}: −ε rather than Baraff's 0), drive it to zero; the most negative first.
  for (;;) {
    int d = -1;
    for (int i = 0; i < n; ++i)
      if (set[i] == ContactSet::Undriven && a[i] < -params.epsilon && (d < 0 || a[i] < a[d])) d = i;
    if (d < 0) break;
    // drive_to_zero(d).
    for (;;) {
      if (result.pivots >= maxPivots) {
        result.converged = false;
        result.failure = "pivot limit reached (cycling)";
        break;
      }
      const VecX df = forceDirection(A, set, d, params.linearSolver);
      const VecX da = A * df;
      const auto [s, j] = maxStep(f, a, df, da, set, d);
      ++result.pivots;
      if (j < 0) {
        result.converged = false;
        result.failure = "contact " + std::to_string(d) + " cannot be driven to zero";
        break;
      }
      f += s * df;
      a += s * da;
      if (j == d) {
        set[d] = ContactSet::Clamped;
        a[d] = 0.0;
        break;
      }
      if (set[j] == ContactSet::Clamped) {
        set[j] = ContactSet::NotClamped;
        f[j] = 0.0;
      } else {
        set[j] = ContactSet::Clamped;
        a[j] = 0.0;
      }
    }
    if (!result.converged) break;
    // Undriven contacts the ε lets pass keep f = 0, as not clamped ones do.
  }
  // \thesis{§3.3.1}: forces the tolerance left negative would pull the bodies together.
  if (params.clampNegativeForces) f = f.cwiseMax(0.0);
  a = A * f + b;
  return result;
}

double lcpViolation(const MatX& A, const VecX& b, const VecX& f) {
  requireProblem(A, b);
  if (b.size() == 0) return 0.0;
  const VecX a = A * f + b;
  const double aScale = std::max(1.0, b.cwiseAbs().maxCoeff());
  const double diagonal = A.size() ? A.diagonal().maxCoeff() : 1.0;
  const double fScale = aScale / std::max(1e-12, diagonal);
  double worst = 0.0;
  for (int i = 0; i < f.size(); ++i) {
    worst = std::max(worst, -f[i] / fScale);
    worst = std::max(worst, -a[i] / aScale);
    worst = std::max(worst, std::abs(f[i] * a[i]) / (fScale * aScale));
  }
  return worst;
}

}  // namespace boxsim
