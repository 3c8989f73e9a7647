/// \file
/// Sub-commands of the `boxsim` command line (CLI11).
#pragma once

#include <CLI/CLI.hpp>

#include "boxsim/filtering/filter_choice.hpp"

namespace boxsim::cli {

/// Adds `boxsim run SCENE.json [--method M] [--dt S] [--duration S] [--out TRAJ.dat]`
/// (docs/cli.md: defaults, output files, exit statuses).
void addRunCommand(CLI::App& app);
/// Adds `boxsim render TRAJ.dat --out FILE.png|FILE.gif|FILE.svg [--frame N ...]`.
void addRenderCommand(CLI::App& app);
/// Adds `boxsim filter TRAJ.dat --filter box|envelope [parameters] --out OUT.dat`
/// (\thesis{§5.5}).
void addFilterCommand(CLI::App& app);
/// Adds the options that choose a \thesis{§5.5} filter (`--filter`, `--filter-half-width`,
/// `--envelope-radius`, `--envelope-angle`) to `cmd`, storing them in `choice`; `required`
/// makes `--filter` mandatory.
void addFilterOptions(CLI::App& cmd, FilterChoice& choice, bool required);

}  // namespace boxsim::cli
