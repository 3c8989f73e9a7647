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

/// The Cholesky factor L Lᵀ = A_CC of the clamped set, grown a row at a time as contacts are
/// clamped (O(m²) per contact instead of O(m³) per pivot; \thesis{§5.3} points to such
/// updates, after Davis and Hager's modifiable factorisations). A contact leaving the set
/// makes it refactor from the remaining ones in order. A contact whose row depends on the
/// clamped ones (redundant contacts: a singular A_CC) cannot be appended: the factor is then
/// given up for the rest of the solve and fdirection falls back to a pivoted LDLᵀ.
class ClampedFactor {
 public:
  explicit ClampedFactor(const MatX& A) : A_(A), L_(A.rows(), A.rows()) {}

  bool usable() const { return usable_; }
  const std::vector<int>& order() const { return order_; }

  /// Appends contact i; false (and the factor given up) when A_CC would be singular.
  bool append(int i) {
    if (!usable_) return false;
    const int m = static_cast<int>(order_.size());
    VecX l(m);
    for (int r = 0; r < m; ++r) {
      double sum = A_(order_[r], i);
      for (int c = 0; c < r; ++c) sum -= L_(r, c) * l[c];
      l[r] = sum / L_(r, r);
    }
    const double pivot = A_(i, i) - l.squaredNorm();
    // Relative to the diagonal: below this the new row is a combination of the others up to
    // rounding (four coplanar corners leave exactly 0 up to a few ulp).
    if (!(pivot > kDependentPivot * A_(i, i))) {
      usable_ = false;
      return false;
    }
    for (int c = 0; c < m; ++c) L_(m, c) = l[c];
    L_(m, m) = std::sqrt(pivot);
    order_.push_back(i);
    return true;
  }

  /// Removes contact i and refactors the rest in their order.
  void remove(int i) {
    std::vector<int> rest;
    for (int k : order_)
      if (k != i) rest.push_back(k);
    order_.clear();
    for (int k : rest)
      if (!append(k)) return;
  }

  /// x with A_CC x = rhs, rhs and x in order() order.
  VecX solve(const VecX& rhs) const {
    const int m = static_cast<int>(order_.size());
    VecX y(m);
    for (int r = 0; r < m; ++r) {
      double sum = rhs[r];
      for (int c = 0; c < r; ++c) sum -= L_(r, c) * y[c];
      y[r] = sum / L_(r, r);
    }
    VecX x(m);
    for (int r = m - 1; r >= 0; --r) {
      double sum = y[r];
      for (int c = r + 1; c < m; ++c) sum -= L_(c, r) * x[c];
      x[r] = sum / L_(r, r);
    }
    return x;
  }

 private:
  static constexpr double kDependentPivot = 1e-10;
  const MatX& A_;
  MatX L_;
  std::vector<int> order_;
  bool usable_ = true;
};

/// fdirection(d) of Baraff 1994, §5: the change of the forces that moves a_d while every
/// clamped contact keeps a = 0 and every other force stays put: Δf_d = 1, Δf_C solves
/// A_CC Δf_C = −A_Cd, the rest is 0.
VecX forceDirection(const MatX& A, const std::vector<ContactSet>& set, int d,
                    LcpLinearSolver solver, const ClampedFactor* factor) {
  const int n = static_cast<int>(A.rows());
  VecX df = VecX::Zero(n);
  df[d] = 1.0;
  if (factor && factor->usable()) {
    const std::vector<int>& order = factor->order();
    VecX rhs(order.size());
    for (std::size_t r = 0; r < order.size(); ++r) rhs[static_cast<int>(r)] = -A(order[r], d);
    const VecX x = factor->solve(rhs);
    for (std::size_t r = 0; r < order.size(); ++r) df[order[r]] = x[static_cast<int>(r)];
    return df;
  }
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
  VecX x;
  if (solver == LcpLinearSolver::CompleteOrthogonal)
    x = Acc.completeOrthogonalDecomposition().solve(rhs);
  else if (solver == LcpLinearSolver::GaussianElimination)
    x = Acc.partialPivLu().solve(rhs);
  else
    x = Acc.ldlt().solve(rhs);
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

std::string lcpLinearSolverName(LcpLinearSolver solver) {
  switch (solver) {
    case LcpLinearSolver::CompleteOrthogonal: return "complete_orthogonal";
    case LcpLinearSolver::Ldlt: return "ldlt";
    case LcpLinearSolver::IncrementalCholesky: return "incremental_cholesky";
    case LcpLinearSolver::GaussianElimination: return "gaussian_elimination";
  }
  return "unknown";
}

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
  ClampedFactor factor(A);
  const ClampedFactor* incremental =
      params.linearSolver == LcpLinearSolver::IncrementalCholesky ? &factor : nullptr;
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
      const VecX df = forceDirection(A, set, d, params.linearSolver, incremental);
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
        if (params.snapToBounds) a[d] = 0.0;
        if (incremental) factor.append(d);
        break;
      }
      if (set[j] == ContactSet::Clamped) {
        set[j] = ContactSet::NotClamped;
        if (params.snapToBounds) f[j] = 0.0;
        if (incremental) factor.remove(j);
      } else {
        set[j] = ContactSet::Clamped;
        if (params.snapToBounds) a[j] = 0.0;
        if (incremental) factor.append(j);
      }
    }
    if (!result.converged) break;
    // Undriven contacts the ε lets pass keep f = 0, as not clamped ones do.
  }
  // \thesis{§3.3.1}: forces the tolerance left negative would pull the bodies together.
  if (n > 0) result.mostNegativeForce = std::min(0.0, f.minCoeff());
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
