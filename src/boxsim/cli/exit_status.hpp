/// \file
/// The exit statuses of the `boxsim` command (listed for users in docs/cli.md), the error that
/// carries one out of a sub-command, and how errors are printed.
#pragma once

#include <sysexits.h>

#include <CLI/CLI.hpp>
#include <functional>
#include <string>

namespace boxsim::cli {

/// What a `boxsim` sub-command's exit status means. The small numbers are the command's own;
/// the ones for files are the BSD sysexits codes (<sysexits.h>), which scripts already know.
enum class ExitStatus : int {
  /// Done (also for --help).
  Ok = 0,
  /// The work itself failed: a body's state stopped being finite, gnuplot could not draw,
  /// memory ran out.
  Failure = 1,
  /// The command line: an unknown or missing option or argument, a value out of range,
  /// options that contradict each other, an output path that names an input.
  Usage = 2,
  /// An input file that does not follow its format: a scene (docs/scene_format.md) or a
  /// trajectory file.
  BadInput = 3,
  /// An input file that does not exist or cannot be read (EX_NOINPUT, 66).
  NoInput = EX_NOINPUT,
  /// The output cannot be created: its folder is missing or not writable, or a folder or a
  /// device stands at its path (EX_CANTCREAT, 73). Checked before any work is done.
  CannotCreate = EX_CANTCREAT,
  /// Reading or writing failed midway, as on a full disk (EX_IOERR, 74). The output is left as
  /// it was and no temporary file stays behind.
  IoError = EX_IOERR,
};

/// One line per exit status, for the end of every help page.
extern const char* const kExitStatusHelp;

/// An error that ends a sub-command with `status`; main() prints its message as
/// "boxsim COMMAND: error: MESSAGE".
class CommandError : public CLI::Error {
 public:
  /// An error with `message` (what went wrong and how to fix it) and its exit status.
  CommandError(const std::string& message, ExitStatus status);
};

/// Runs a sub-command's body and turns what it throws into a CommandError with the status of
/// its kind: std::logic_error (std::invalid_argument from a check of the options) gives Usage;
/// SceneError and TrajectoryFormatError BadInput; CannotCreateError CannotCreate; WriteError
/// IoError; anything else (std::bad_alloc included) Failure. CLI11's errors pass unchanged.
void runGuarded(const std::function<void()>& body);

/// Sets `app` and its sub-commands (add them first) up for these statuses: every help page
/// ends with kExitStatusHelp, and every error is printed as "boxsim COMMAND: error: MESSAGE",
/// usage errors followed by a pointer to --help.
void configureExits(CLI::App& app);

/// Prints `error`, caught around app.parse(), as configureExits() set up (or the help page it
/// asks for) and returns the exit status: its own for a CommandError, 0 for --help, Usage for
/// every other error of CLI11 (whose own codes, 105 and up, are not used).
int exitStatusOf(const CLI::App& app, const CLI::Error& error);

}  // namespace boxsim::cli
