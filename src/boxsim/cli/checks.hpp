/// \file
/// Checks a `boxsim` sub-command makes of its command line before any work: the files it
/// names and the numbers it is given.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace boxsim::cli {

/// Throws CommandError(NoInput) naming `what` ("scene file") and `path` when the file does not
/// exist, is a folder, or cannot be opened for reading.
void requireReadableInput(const std::string& path, const std::string& what);

/// Throws CommandError(Usage) when `output` names one of `inputs`: the same file, through
/// symbolic or hard links too. Writing it would replace the input with the output.
void requireDistinctOutput(const std::string& output, const std::vector<std::string>& inputs);

/// A CLI11 validator for a finite number above `lowest` (at least `lowest` when `inclusive`)
/// in `unit`; its message names the value and the range ("'0' is not a finite number > 0 s").
CLI::Validator finiteNumber(double lowest, bool inclusive, const std::string& unit);

}  // namespace boxsim::cli
