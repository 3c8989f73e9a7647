/// \file
/// The header of every data file of the impulse chapter's figures.
#pragma once

#include <string>

#include "boxsim/techniques.hpp"

namespace boxsim {

/// "# title", Δt and the scenes' folder, every parameter of the impulse and damped steppers as
/// the chapter runs them (their defaults), and "# columns: ...".
inline std::string header(const std::string& title, const std::string& columns) {
  // Every run of the chapter uses the default parameters of its stepper: list them all.
  std::string out = "# " + title + "\n# dt: 1/60 s; scenes: chapters/impulse_damped/scenes/\n";
  for (const char* method : {"impulse", "damped"})
    for (const auto& [key, value] : makeStepper(method)->parameters())
      out += "# " + std::string(method) + "." + key + ": " + value + "\n";
  return out + "# columns: " + columns + "\n";
}

}  // namespace boxsim
