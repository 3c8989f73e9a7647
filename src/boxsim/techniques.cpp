#include "boxsim/techniques.hpp"

#include <stdexcept>

#include "boxsim/analytic_lcp/analytic_stepper.hpp"
#include "boxsim/basic_colliding/basic_colliding.hpp"
#include "boxsim/impulse_damped/damped_integration.hpp"
#include "boxsim/impulse_damped/impulse_stepper.hpp"
#include "boxsim/timewarp/timewarp.hpp"

namespace boxsim {

std::vector<std::string> methodNames() {
  return {"basic_colliding", "analytic", "impulse", "damped", "timewarp_simple", "timewarp_safer",
          "timewarp_swept"};
}

std::unique_ptr<Stepper> makeStepper(const std::string& method, const TechniqueOptions& options) {
  const auto refuse = [&](bool given, const char* option) {
    if (given)
      throw std::invalid_argument("the method '" + method + "' takes no " + option + " option");
  };
  if (method == "basic_colliding") {
    refuse(options.contactNormal.has_value(), "contact normal");
    refuse(options.contactGathering.has_value(), "contact gathering");
    refuse(options.sleep.has_value(), "sleep");
    refuse(options.continuousCollision.has_value(), "continuous collision");
    refuse(options.plausibilitySeed.has_value(), "plausibility seed");
    BasicCollidingParams params;
    if (options.integrator) params.integrator = *options.integrator;
    return std::make_unique<BasicCollidingStepper>(params);
  }
  if (method == "analytic") {
    refuse(options.contactNormal.has_value(), "contact normal");
    refuse(options.contactGathering.has_value(), "contact gathering");
    refuse(options.sleep.has_value(), "sleep");
    refuse(options.continuousCollision.has_value(), "continuous collision");
    refuse(options.plausibilitySeed.has_value(), "plausibility seed");
    AnalyticParams params;
    if (options.integrator) params.loop.integrator = *options.integrator;
    return std::make_unique<AnalyticStepper>(params);
  }
  for (const TimewarpVariant variant :
       {TimewarpVariant::Simple, TimewarpVariant::Safer, TimewarpVariant::Swept}) {
    if (method != timewarpMethodName(variant)) continue;
    refuse(options.contactNormal.has_value(), "contact normal");
    refuse(options.contactGathering.has_value(), "contact gathering");
    refuse(options.sleep.has_value(), "sleep");
    refuse(options.continuousCollision.has_value(), "continuous collision");
    refuse(options.plausibilitySeed.has_value(), "plausibility seed");
    TimewarpParams params;
    params.variant = variant;
    if (options.integrator) params.integrator = *options.integrator;
    return std::make_unique<TimewarpStepper>(params);
  }
  if (method == "impulse") {
    refuse(options.sleep.has_value(), "sleep");
    refuse(options.continuousCollision.has_value(), "continuous collision");
    refuse(options.plausibilitySeed.has_value(), "plausibility seed");
    ImpulseStepperParams params;
    if (options.contactNormal) params.impulse.normalModel = *options.contactNormal;
    if (options.contactGathering) params.impulse.gathering = *options.contactGathering;
    if (options.integrator) params.impulse.integrator = *options.integrator;
    return std::make_unique<ImpulseStepper>(params);
  }
  if (method == "damped") {
    DampedIntegrationParams params;
    if (options.contactNormal) params.impulse.normalModel = *options.contactNormal;
    if (options.contactGathering) params.impulse.gathering = *options.contactGathering;
    if (options.sleep) params.sleep.enabled = *options.sleep;
    if (options.continuousCollision) params.continuousCollision.enabled = *options.continuousCollision;
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
