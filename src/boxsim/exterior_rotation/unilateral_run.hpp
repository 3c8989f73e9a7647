/// \file
/// The exterior rotation problem in the thesis' own setting (\thesis{§6.2}): the boxes of
/// Figs. 6.1–6.3 under frictionless, unilateral contact forces, the LCP of Baraff (1994) with
/// \thesis{§3.3.1}'s ε and clamp (analytic_lcp/), solved for the instant at the start of each
/// step and held over it by forward Euler, "the most basic forward Euler scheme used in our
/// implementation". No collision handling and no drift correction: what integration alone does
/// to the contacts is measured, as the thesis states it ("integration of these forces may lead
/// to incorrectly interpenetrating or separating objects").
///
/// Without friction nothing sticks: a box over the table's edge tips and slides off it, the
/// stacked cubes of Fig. 6.1 slide on one another, and B slides on A in Fig. 6.3. The
/// bilateral sticking model of sticking_forces.hpp is the thesis' figures' premise ("a very
/// high degree of static friction"); this one is the model the thesis' code solved (contact
/// forces "calculated assuming no friction", §5.4). The chapter page compares the two.
#pragma once

#include <vector>

#include "boxsim/analytic_lcp/lcp_solver.hpp"
#include "boxsim/core/integrator.hpp"
#include "boxsim/exterior_rotation/sticking_scene.hpp"

namespace boxsim {

/// Settings of runUnilateral().
struct UnilateralParams {
  /// The LCP: the thesis' ε (1e-5 m/s²) and clamp; Gaussian elimination, the thesis' solver.
  LcpParams lcp = [] {
    LcpParams p;
    p.linearSolver = LcpLinearSolver::GaussianElimination;
    return p;
  }();
  /// m: contacts closer than this get a row of the LCP (the analytic method's contact margin).
  double contactMargin = 1e-3;
  /// How the forces are held over the step: forward Euler, as the thesis.
  Integrator integrator = Integrator::ForwardEuler;
};

/// One instant of a unilateral run.
struct UnilateralSample {
  double t = 0.0;  ///< s
  /// deepestPenetration() (collision/broad_phase.hpp) over every pair, m: interpenetration.
  double penetration = 0.0;
  /// Per hinge contact of the scene (StickingScene::pivots), the signed depth of its two
  /// bodies, m: the separating-axis overlap when they overlap (> 0), minus their distance
  /// along the best separating axis when apart (< 0), 0 when touching.
  std::vector<double> hingeDepth;
  int contacts = 0;  ///< point contacts in the step's LCP
};

/// The result of runUnilateral().
struct UnilateralRun {
  std::vector<UnilateralSample> samples;  ///< t = 0, Δt, …, N Δt
  World end;                              ///< the world at the end
  double maxPenetration = 0.0;            ///< m, over the samples
};

/// Runs the world of `scene` for `steps` steps of dt (s) under frictionless unilateral LCP
/// forces held over each step (file comment), sampling after every step and at t = 0.
/// \throws std::invalid_argument for steps < 1 or dt not positive and finite.
UnilateralRun runUnilateral(const StickingScene& scene, double dt, int steps,
                            const UnilateralParams& params = {});

}  // namespace boxsim
