/// \file
/// The measures of the exterior rotation problem (\thesis{§6.2}) and a run that records them:
/// how deep the boxes overlap, how far each pair of sticking points has drifted apart or into
/// each other, and how far the top box has left the circle it should follow, against the
/// reduced-coordinate reference of hinge_reference.hpp.
#pragma once

#include <functional>
#include <vector>

#include "boxsim/exterior_rotation/hinge_reference.hpp"
#include "boxsim/exterior_rotation/sticking_integrators.hpp"

namespace boxsim {

/// The signed drift of sticking point `i` of `scene`: (p_b − p_a) · n, n its contact normal
/// from a into b, m. Positive: the material points have separated; negative: b has moved into a.
double pointGap(const StickingScene& scene, int i);

/// Everything measured at one instant of a run.
struct StickingSample {
  double t = 0.0;            ///< s
  double penetration = 0.0;  ///< deepestPenetration() (collision/broad_phase.hpp), m
  double maxError = 0.0;     ///< max over points of |p_b − p_a| (normal and tangential drift), m
  double minGap = 0.0;       ///< the most negative pointGap() (interpenetration), m
  double maxGap = 0.0;       ///< the most positive pointGap() (separation), m
  std::vector<double> contactGap;  ///< per contact, the mean pointGap() of its points, m
  /// The top body's distance from its hinge (the simulated material hinge point on the link
  /// below, or the table's edge) minus that distance at t = 0, m: + outside the circle.
  double radialError = 0.0;
  double referenceError = 0.0;  ///< |top centre − the reference's top centre|, m
  Vec3 top = Vec3::Zero();           ///< the top body's centre, m
  Vec3 topReference = Vec3::Zero();  ///< the reference's top centre, m
  /// Per link, the load on its hinge contact (StickingScene::pivots) from the sticking solve at
  /// this state: its normal force must stay > 0.
  std::vector<ContactLoad> pivotLoads;
  double energyChange = 0.0;           ///< (kinetic + potential) − its value at t = 0, J
  double referenceEnergyChange = 0.0;  ///< the same for the reference, J
  Eigen::VectorXd referenceAngles;     ///< the reference's hinge angles φ_k, rad
};

/// The extremes of a run's samples.
struct StickingSummary {
  double maxPenetration = 0.0;  ///< m
  double maxError = 0.0;        ///< max |p_b − p_a|, m
  double minGap = 0.0;          ///< most negative gap (<= 0), m
  double maxGap = 0.0;          ///< most positive gap (>= 0), m
  double maxAbsRadialError = 0.0;   ///< m
  double maxReferenceError = 0.0;   ///< m
  double minPivotNormal = 0.0;      ///< smallest normal force on any hinge contact, N
  double maxRequiredMu = 0.0;       ///< largest |f_t| / f_n on any hinge contact
  double maxAbsReferenceEnergyChange = 0.0;  ///< the reference's energy drift, J
};

/// The result of runSticking().
struct StickingRun {
  std::vector<StickingSample> samples;  ///< t = 0, Δt, …, N Δt
  StickingScene end;                    ///< the scene at the end of the run
  StickingSummary summary;              ///< extremes over the samples
};

/// Runs `scene` from its initial state for `steps` steps of dt (s) with `method`, sampling
/// every measure at t = 0 and after every step against a HingeReference run alongside.
/// `onStep`, when given, sees the world after every step (and at t = 0) with its time.
/// \throws std::invalid_argument for steps < 1 or dt as stepSticking().
StickingRun runSticking(const StickingScene& scene, StickingMethod method, double dt, int steps,
                        const std::function<void(const World&, double)>& onStep = {});

/// The order of convergence of an error against the step: the least-squares slope of
/// log(error) on log(dt) (GSL's gsl_fit_linear). `dt` (s) and `error` have the same size >= 2
/// and hold positive numbers. \throws std::invalid_argument otherwise.
double convergenceOrder(const std::vector<double>& dt, const std::vector<double>& error);

}  // namespace boxsim
