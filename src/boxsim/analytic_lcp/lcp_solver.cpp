/// \file
/// Baraff's pivoting method for the contact LCP (Baraff 1994, §4–5; \thesis{§3.3.1}).
#include "boxsim/analytic_lcp/lcp_solver.hpp"

#include <Eigen/Dense>
#include <Eigen/SparseCore>

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

/// The Cholesky factor L Lᵀ of A_BB, B the independent contacts of the clamped set, grown a
/// row at a time as contacts are clamped (O(m²) per contact instead of O(m³) per pivot;
/// \thesis{§5.3} points to such updates, after Davis and Hager's modifiable factorisations).
///
/// Redundant contacts (a singular A_CC, such as four coplanar corners on a plane) are kept out
/// of B: a clamped contact r whose row of J depends on those of B has a_r = Σ α_k a_k = 0
/// whatever the forces of B do, so it keeps its force (Δf_r = 0) and the direction solves for
/// B alone. A contact of B leaving the clamped set is removed from the factor by a rank-one
/// update of the rows below it (O(m²), Golub and Van Loan §6.5.4, as Davis and Hager's
/// row deletion), and the clamped contacts kept out are offered to B again, in the order they
/// were clamped: without the one that left, their rows may have become independent.
class ClampedFactor {
 public:
  explicit ClampedFactor(const MatX& A)
      : A_(A), L_(A.rows(), A.rows()), inB_(static_cast<std::size_t>(A.rows()), 0) {}

  /// B, in factor order.
  const std::vector<int>& order() const { return order_; }

  /// Contact i joins the clamped set: appended to B unless its row depends on B's.
  void clamp(int i) {
    clamped_.push_back(i);
    append(i);
  }

  /// Contact i leaves the clamped set.
  void unclamp(int i) {
    clamped_.erase(std::find(clamped_.begin(), clamped_.end(), i));
    if (!inB_[i]) return;
    removeAt(static_cast<int>(std::find(order_.begin(), order_.end(), i) - order_.begin()));
    for (int k : clamped_)
      if (!inB_[k]) append(k);
  }

  /// x with A_BB x = rhs, rhs and x in order() order.
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
  /// Appends contact i to B when its row is independent of B's.
  void append(int i) {
    const int m = static_cast<int>(order_.size());
    VecX l(m);
    for (int r = 0; r < m; ++r) {
      double sum = A_(order_[r], i);
      for (int c = 0; c < r; ++c) sum -= L_(r, c) * l[c];
      l[r] = sum / L_(r, r);
    }
    const double pivot = A_(i, i) - l.squaredNorm();
    // Relative to the diagonal: below this the new row is a combination of B's up to
    // rounding (four coplanar corners leave 0 up to a few ulp) or so nearly one that the
    // factor would amplify rounding by 1/√pivot.
    if (!(pivot > kDependentPivot * A_(i, i))) return;
    for (int c = 0; c < m; ++c) L_(m, c) = l[c];
    L_(m, m) = std::sqrt(pivot);
    order_.push_back(i);
    inB_[i] = 1;
  }

  /// Deletes row and column p of A_BB from the factor. Rows below p move up a row and their
  /// columns after p left a column; the trailing block L₃₃ then needs L₃₃' L₃₃'ᵀ =
  /// L₃₃ L₃₃ᵀ + x xᵀ, x the deleted column below p, one Givens-like sweep over it.
  void removeAt(int p) {
    const int m = static_cast<int>(order_.size());
    const int k = m - p - 1;
    VecX x = L_.col(p).segment(p + 1, k);
    for (int c = 0; c < p; ++c)
      for (int i = p + 1; i < m; ++i) L_(i - 1, c) = L_(i, c);
    for (int c = p + 1; c < m; ++c)
      for (int i = c; i < m; ++i) L_(i - 1, c - 1) = L_(i, c);
    for (int j = 0; j < k; ++j) {
      const int col = p + j;
      const double diagonal = L_(col, col);
      // √(d² + x²) as written, not hypot, which C libraries round differently (docs/web.md);
      // the factor's entries are far from overflow.
      const double r = std::sqrt(diagonal * diagonal + x[j] * x[j]);
      const double cosine = r / diagonal, sine = x[j] / diagonal;
      L_(col, col) = r;
      for (int i = j + 1; i < k; ++i) {
        L_(p + i, col) = (L_(p + i, col) + sine * x[i]) / cosine;
        x[i] = cosine * x[i] - sine * L_(p + i, col);
      }
    }
    inB_[order_[p]] = 0;
    order_.erase(order_.begin() + p);
  }

  static constexpr double kDependentPivot = 1e-8;
  const MatX& A_;
  MatX L_;
  std::vector<int> clamped_;  // in the order they were clamped
  std::vector<int> order_;
  std::vector<char> inB_;     // per contact: in B
};

/// fdirection(d) of Baraff 1994, §5: the change of the forces that moves a_d while every
/// clamped contact keeps a = 0 and every other force stays put: Δf_d = 1, Δf_C solves
/// A_CC Δf_C = −A_Cd, the rest is 0.
VecX forceDirection(const MatX& A, const std::vector<ContactSet>& set, int d,
                    LcpLinearSolver solver, const ClampedFactor* factor) {
  const int n = static_cast<int>(A.rows());
  VecX df = VecX::Zero(n);
  df[d] = 1.0;
  if (factor) {
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
///
/// Rates of change smaller than this share of the largest are rounding (see maxStep).
constexpr double kRoundingRate = 1e-12;

/// DEVIATION(Baraff 1994 §5, exact comparisons): a contact already at its bound (a clamped
/// one at f = 0, a not clamped one at a = 0) counts as falling only when its rate is below
/// −kRoundingRate of the largest rate of its kind. A redundant contact's true rates are 0 and
/// rounding gives them ±1e-16: compared with 0, such a contact leaves the clamped set on a
/// step of 0 and rejoins it on the next, for ever (measured on a touching pyramid of base 10).
/// Let through, its force or acceleration strays past the bound by rounding only, which the
/// clamp of \thesis{§3.3.1} removes. Contacts away from their bounds are compared exactly.
std::pair<double, int> maxStep(const VecX& f, const VecX& a, const VecX& df, const VecX& da,
                               const std::vector<ContactSet>& set, int d) {
  double s = std::numeric_limits<double>::infinity();
  int j = -1;
  const double dfFalling = -kRoundingRate * df.cwiseAbs().maxCoeff();
  const double daFalling = -kRoundingRate * da.cwiseAbs().maxCoeff();
  if (da[d] > 0.0) {
    s = -a[d] / da[d];
    j = d;
  }
  for (int i = 0; i < static_cast<int>(f.size()); ++i) {
    if (set[i] == ContactSet::Clamped && df[i] < 0.0 && !(f[i] <= 0.0 && df[i] >= dfFalling)) {
      const double si = -f[i] / df[i];
      if (si < s) {
        s = si;
        j = i;
      }
    } else if (set[i] == ContactSet::NotClamped && da[i] < 0.0 &&
               !(a[i] <= 0.0 && da[i] >= daFalling)) {
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
  return enumName(kLcpLinearSolverNames, solver);
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
  // Δa = A Δf at every pivot: A couples only contacts that share a body, a few dozen per row
  // of hundreds, so a sparse copy makes the product O(nonzeros) rather than O(n²).
  const Eigen::SparseMatrix<double> sparseA = A.sparseView();
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
      const VecX da = sparseA * df;
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
        if (incremental) factor.clamp(d);
        break;
      }
      if (set[j] == ContactSet::Clamped) {
        set[j] = ContactSet::NotClamped;
        if (params.snapToBounds) f[j] = 0.0;
        if (incremental) factor.unclamp(j);
      } else {
        set[j] = ContactSet::Clamped;
        if (params.snapToBounds) a[j] = 0.0;
        if (incremental) factor.clamp(j);
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
