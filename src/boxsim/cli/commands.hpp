/// \file
/// Sub-commands of the `boxsim` command line (CLI11).
#pragma once

#include <CLI/CLI.hpp>

namespace boxsim::cli {

/// Adds `boxsim run SCENE.json --method M --dt S --duration S --out TRAJ.dat`.
void addRunCommand(CLI::App& app);
/// Adds `boxsim render TRAJ.dat --out FILE.png|FILE.gif|FILE.svg [--frame N ...]`.
void addRenderCommand(CLI::App& app);

}  // namespace boxsim::cli
