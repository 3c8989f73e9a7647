#include "boxsim/techniques.hpp"

#include <stdexcept>
#include <utility>

#include "boxsim/analytic_lcp/analytic_stepper.hpp"
#include "boxsim/basic_colliding/basic_colliding.hpp"
#include "boxsim/impulse_damped/damped_integration.hpp"
#include "boxsim/impulse_damped/impulse_stepper.hpp"
#include "boxsim/timewarp/timewarp.hpp"

namespace boxsim {

namespace {

/// Throws std::invalid_argument naming the first option given that `method` does not take:
/// the impulse step's (contact normal, contact gathering) unless `takesImpulseOptions`,
/// geometric stability unless `takesGeometricStability`, and those of damped integration alone
/// (sleep, chatter detection, continuous collision, impact passes, plausibility seed).
void refuseOptions(const std::string& method, const TechniqueOptions& options,
                   bool takesImpulseOptions, bool takesGeometricStability = false) {
  const std::pair<bool, const char*> notTaken[] = {
      {!takesGeometricStability && options.geometricStability.has_value(), "geometric stability"},
      {!takesImpulseOptions && options.contactNormal.has_value(), "contact normal"},
      {!takesImpulseOptions && options.contactGathering.has_value(), "contact gathering"},
      {!takesImpulseOptions && options.threads.has_value(), "threads"},
      {!takesImpulseOptions && options.predictedAnchor.has_value(), "predicted anchor"},
      {!takesImpulseOptions && options.exactEdgePairs.has_value(), "exact edge pairs"},
      {!takesImpulseOptions && options.edgeCorners.has_value(), "edge corners"},
      {options.sleep.has_value(), "sleep"},
      {options.chatterDetection.has_value(), "chatter detection"},
      {options.dampSupportedOnly.has_value(), "damp supported only"},
      {options.fixStopApproach.has_value(), "fix stop approach"},
      {options.continuousCollision.has_value(), "continuous collision"},
      {options.impactPasses.has_value(), "impact passes"},
      {options.shockIterations.has_value(), "shock iterations"},
      {options.plausibilitySeed.has_value(), "plausibility seed"},
  };
  for (const auto& [given, option] : notTaken)
    if (given)
      throw std::invalid_argument("the method '" + method + "' takes no " + option + " option");
}

/// The geometric stability mode of `options`, if given, as the analytic method's and damped
/// integration's switch and classifier parameters.
void applyGeometricStability(const TechniqueOptions& options, bool& use,
                             GeometricStabilityParams& params) {
  if (!options.geometricStability) return;
  use = *options.geometricStability != GeometricStabilityMode::Off;
  params.underLoad = *options.geometricStability == GeometricStabilityMode::UnderLoad;
}

}  // namespace

std::vector<std::string> methodNames() {
  return {"basic_colliding", "analytic", "impulse", "damped", "timewarp_simple", "timewarp_safer",
          "timewarp_swept"};
}

std::unique_ptr<Stepper> makeStepper(const std::string& method, const TechniqueOptions& options) {
  if (method == "basic_colliding") {
    refuseOptions(method, options, /*takesImpulseOptions=*/false);
    BasicCollidingParams params;
    if (options.integrator) params.integrator = *options.integrator;
    return std::make_unique<BasicCollidingStepper>(params);
  }
  if (method == "analytic") {
    refuseOptions(method, options, /*takesImpulseOptions=*/false, /*takesGeometricStability=*/true);
    AnalyticParams params;
    if (options.integrator) params.loop.integrator = *options.integrator;
    applyGeometricStability(options, params.useGeometricStability, params.geometricStability);
    return std::make_unique<AnalyticStepper>(params);
  }
  for (const auto& [variant, name] : kTimewarpMethodNames) {
    if (method != name) continue;
    refuseOptions(method, options, /*takesImpulseOptions=*/false);
    TimewarpParams params;
    params.variant = variant;
    if (options.integrator) params.integrator = *options.integrator;
    return std::make_unique<TimewarpStepper>(params);
  }
  if (method == "impulse") {
    refuseOptions(method, options, /*takesImpulseOptions=*/true);
    ImpulseStepperParams params;
    if (options.contactNormal) params.impulse.normalModel = *options.contactNormal;
    if (options.contactGathering) params.impulse.gathering = *options.contactGathering;
    if (options.threads) params.impulse.threads = *options.threads;
    if (options.predictedAnchor) params.impulse.predictedAnchor = *options.predictedAnchor;
    if (options.exactEdgePairs) params.impulse.exactEdgePairs = *options.exactEdgePairs;
    if (options.edgeCorners) params.impulse.edgeCorners = *options.edgeCorners;
    if (options.integrator) params.impulse.integrator = *options.integrator;
    return std::make_unique<ImpulseStepper>(params);
  }
  if (method == "damped") {
    DampedIntegrationParams params;
    if (options.contactNormal) params.impulse.normalModel = *options.contactNormal;
    if (options.contactGathering) params.impulse.gathering = *options.contactGathering;
    if (options.threads) params.impulse.threads = *options.threads;
    if (options.predictedAnchor) params.impulse.predictedAnchor = *options.predictedAnchor;
    if (options.exactEdgePairs) params.impulse.exactEdgePairs = *options.exactEdgePairs;
    if (options.edgeCorners) params.impulse.edgeCorners = *options.edgeCorners;
    applyGeometricStability(options, params.useGeometricStability, params.geometricStability);
    if (options.sleep) params.sleep.enabled = *options.sleep;
    if (options.chatterDetection) params.sleep.chatterDetection = *options.chatterDetection;
    if (options.dampSupportedOnly) params.damping.supportedOnly = *options.dampSupportedOnly;
    if (options.fixStopApproach) params.fixContacts.stopLiftedApproach = *options.fixStopApproach;
    if (options.continuousCollision) params.continuousCollision.enabled = *options.continuousCollision;
    if (options.impactPasses) params.impactPasses = *options.impactPasses;
    if (options.shockIterations) params.shockIterations = *options.shockIterations;
    if (options.integrator) params.impulse.integrator = *options.integrator;
    if (options.plausibilitySeed) {
      params.plausibility.enabled = true;
      params.plausibility.seed = *options.plausibilitySeed;
    }
    return std::make_unique<DampedIntegrationStepper>(params);
  }
  std::string known;
  for (const std::string& m : methodNames()) known += (known.empty() ? "" : ", ") + m;
  throw std::invalid_argument("unknown method '" + method + "'; known methods: " + known);
}

}  // namespace boxsim
