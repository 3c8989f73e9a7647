/// \file
/// Baraff's pivoting method for the frictionless contact LCP (D. Baraff, "Fast Contact Force
/// Computation for Nonpenetrating Rigid Bodies", SIGGRAPH 1994, §4–5: compute_forces,
/// drive_to_zero, fdirection, maxstep), with the two changes of \thesis{§3.3.1}: the outer loop
/// runs while some a_d < −ε rather than < 0, and forces still negative at the end are set to
/// zero. Both are switchable, so the failure the thesis reports without the clamp can be shown.
///
/// The problem: given A (n × n, symmetric positive semidefinite) and b (n), find f with
///
///     a = A f + b,   f >= 0,   a >= 0,   f_i a_i = 0 for every i,
///
/// f the contact force magnitudes (N) and a the normal accelerations of the contact points
/// (m/s², positive when they separate). For symmetric positive semidefinite A, a is the same
/// for every solution, f is not when A is singular (redundant contacts, such as the four corners
/// of a box on a plane).
#pragma once

#include <string>

#include "boxsim/core/enum_names.hpp"
#include "boxsim/core/math.hpp"

namespace boxsim {

/// A dynamic-size matrix: the contact count changes from step to step.
using MatX = Eigen::MatrixXd;
/// A dynamic-size vector, one entry per contact.
using VecX = Eigen::VectorXd;

/// How the linear system of fdirection, A_CC x = −A_Cd, is solved (Baraff 1994, §5).
enum class LcpLinearSolver {
  /// Eigen's CompleteOrthogonalDecomposition, refactored at every pivot: the minimum-norm
  /// least-squares solution, so a singular A_CC (redundant contacts) still gives a direction.
  CompleteOrthogonal,
  /// Eigen's LDLᵀ with pivoting (LDLT), refactored at every pivot; a zero pivot (singular
  /// A_CC) contributes nothing to the solution, which again keeps a consistent system solved.
  Ldlt,
  /// A Cholesky factor of A_CC grown by a row as each contact is clamped and rebuilt when one
  /// leaves (the updated symmetric factorisation \thesis{§5.3} points to); once a redundant
  /// contact would make A_CC singular, Ldlt for the rest of the solve.
  IncrementalCholesky,
  /// Gaussian elimination with partial pivoting (Eigen's PartialPivLU), refactored at every
  /// pivot: what \thesis{§3.3.1} used. On a singular A_CC (redundant contacts) its zero pivot
  /// is rounding noise, and the direction it returns is noise of that size: kept to reproduce
  /// the thesis' failure without the force clamp, not for use.
  GaussianElimination,
};

/// The solver's name in scene files and output headers: "incremental_cholesky", "ldlt",
/// "complete_orthogonal" or "gaussian_elimination".
std::string lcpLinearSolverName(LcpLinearSolver solver);

/// The names of the linear solvers.
inline constexpr EnumNames<LcpLinearSolver, 4> kLcpLinearSolverNames{{
    {LcpLinearSolver::CompleteOrthogonal, "complete_orthogonal"},
    {LcpLinearSolver::Ldlt, "ldlt"},
    {LcpLinearSolver::IncrementalCholesky, "incremental_cholesky"},
    {LcpLinearSolver::GaussianElimination, "gaussian_elimination"},
}};

/// Parameters of solveContactLcp.
struct LcpParams {
  /// ε of \thesis{§3.3.1}, in the units of a (m/s²): the outer loop drives contacts whose
  /// acceleration is below −ε. 1e-5, the thesis' value. 0 reproduces Baraff's a_d < 0.
  double epsilon = 1e-5;
  /// \thesis{§3.3.1}'s post-processing: forces still negative when the loop ends are set to
  /// zero (they would pull the bodies together). Off reproduces the failure the thesis saw.
  bool clampNegativeForces = true;
  /// When a pivot moves contact j between the sets, set f_j (leaving the clamped set) or a_j
  /// (joining it) to exactly 0 rather than to the rounded f_j + s Δf_j or a_j + s Δa_j.
  /// DEVIATION(Baraff 1994 §5, drive_to_zero as written): with the bound met exactly no
  /// rounding error accumulates in the sets' conditions over the pivots. Off is Baraff's
  /// procedure as printed.
  bool snapToBounds = true;
  /// How fdirection's linear system is solved. LDLᵀ, the complete orthogonal decomposition and
  /// the incremental factor cope with redundant contacts; the incremental factor is the fastest
  /// while the clamped set is independent.
  /// DEVIATION(\thesis{§3.3.1}): the thesis solved it by Gaussian elimination
  /// (LcpLinearSolver::GaussianElimination), whose zero pivot on redundant contacts returns a
  /// direction of rounding noise; the default is the incremental Cholesky factor.
  LcpLinearSolver linearSolver = LcpLinearSolver::IncrementalCholesky;
  /// Guard against cycling: at most this many pivots (maxstep events) in all, as a multiple
  /// of n. Baraff proves termination for positive definite A; rounding can still cycle.
  int maxPivotsPerContact = 50;
};

/// What solveContactLcp found.
struct LcpResult {
  VecX f;               ///< N, one force magnitude per contact, >= 0 when clamped
  VecX a;               ///< m/s², A f + b for the returned f
  int pivots = 0;       ///< maxstep events taken
  /// N, the most negative force before the clamp of \thesis{§3.3.1} (0 when none was
  /// negative): what the clamp removed, or what is left in f when it is off.
  double mostNegativeForce = 0.0;
  bool converged = true;  ///< false when the pivot guard or an unbounded step stopped it
  std::string failure;  ///< why it stopped early, empty when converged
};

/// Solves the contact LCP (A, b) by Baraff's method as described in the file comment.
/// A must be square and symmetric with b of matching size; throws std::invalid_argument when
/// the shapes disagree or an entry is not finite.
LcpResult solveContactLcp(const MatX& A, const VecX& b, const LcpParams& params = {});

/// The worst violation of the LCP conditions by (f, a), each scaled by the problem:
/// max over i of max(−f_i / fScale, −a_i / aScale, |f_i a_i| / (fScale aScale)), where
/// aScale = max(1, |b|_∞) and fScale = aScale / max(1e-12, max_i A_ii). 0 for an exact solution.
double lcpViolation(const MatX& A, const VecX& b, const VecX& f);

}  // namespace boxsim
