/// \file
/// The exterior rotation problem in the thesis' own setting (\thesis{§6.2}): the boxes of
/// Figs. 6.1–6.3 under frictionless, unilateral contact forces, the LCP of Baraff (1994) with
/// \thesis{§3.3.1}'s ε and clamp as the analytic method solves it (AnalyticStepper::
/// contactWrenches), for the instant at the start of each step, and held over the step by
/// forward Euler, "the most basic forward Euler scheme used in our implementation". No collision handling and no drift correction: what integration alone does
/// to the contacts is measured, as the thesis states it ("integration of these forces may lead
/// to incorrectly interpenetrating or separating objects").
///
/// Without friction nothing sticks: a box over the table's edge tips and slides off it, the
/// stacked cubes of Fig. 6.1 slide on one another, and B slides on A in Fig. 6.3. The
/// bilateral sticking model of sticking_forces.hpp is the thesis' figures' premise ("a very
/// high degree of static friction"); this one is the model the thesis' code solved (contact
/// forces "calculated assuming no friction", §5.4). The chapter page compares the two.
#pragma once

#include <limits>
#include <vector>

#include "boxsim/analytic_lcp/analytic_stepper.hpp"
#include "boxsim/core/integrator.hpp"
#include "boxsim/exterior_rotation/sticking_scene.hpp"

namespace boxsim {

/// Settings of runUnilateral().
struct UnilateralParams {
  /// The contact forces: the analytic method's (AnalyticStepper::contactWrenches: the contact
  /// areas within its margin, Baraff's LCP) with the thesis' ε and clamp, Gaussian elimination
  /// (its solver) and no drift correction (it had none). Every contact point within the margin
  /// takes part, however fast it approaches (restingSpeed infinite): with no collision loop
  /// here, a contact left to it would get no force at all.
  AnalyticParams analytic = [] {
    AnalyticParams p;
    p.lcp.linearSolver = LcpLinearSolver::GaussianElimination;
    p.driftCorrection = false;
    p.restingSpeed = std::numeric_limits<double>::infinity();
    return p;
  }();
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
