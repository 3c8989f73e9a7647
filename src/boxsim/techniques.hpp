/// \file
/// The registry of techniques: the method names the command line and the drivers accept,
/// and the stepper each one builds.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "boxsim/core/integrator.hpp"
#include "boxsim/core/stepper.hpp"

namespace boxsim {

/// Options shared by every technique that a command line can set.
struct TechniqueOptions {
  /// Integrator between collisions (basic_colliding only; the impulse-based techniques
  /// integrate semi-implicitly by construction); empty: the technique's own default.
  std::optional<Integrator> integrator;
};

/// The method names, in the order the thesis introduces them.
std::vector<std::string> methodNames();

/// Builds the stepper of a method. Throws std::invalid_argument naming the unknown method and
/// listing the known ones.
std::unique_ptr<Stepper> makeStepper(const std::string& method, const TechniqueOptions& options = {});

}  // namespace boxsim
