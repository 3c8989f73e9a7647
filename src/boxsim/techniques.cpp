#include "boxsim/techniques.hpp"

#include <stdexcept>

#include "boxsim/basic_colliding/basic_colliding.hpp"
#include "boxsim/impulse_damped/damped_integration.hpp"
#include "boxsim/impulse_damped/impulse_stepper.hpp"

namespace boxsim {

std::vector<std::string> methodNames() { return {"basic_colliding", "impulse", "damped"}; }

std::unique_ptr<Stepper> makeStepper(const std::string& method, const TechniqueOptions& options) {
  if (method == "basic_colliding") {
    BasicCollidingParams params;
    if (options.integrator) params.integrator = *options.integrator;
    return std::make_unique<BasicCollidingStepper>(params);
  }
  if (method == "impulse") return std::make_unique<ImpulseStepper>();
  if (method == "damped") return std::make_unique<DampedIntegrationStepper>();
  std::string known;
  for (const std::string& m : methodNames()) known += (known.empty() ? "" : ", ") + m;
  throw std::invalid_argument("unknown method '" + method + "'; known methods: " + known);
}

}  // namespace boxsim
