#include "boxsim/cli/exit_status.hpp"

#include <new>
#include <stdexcept>

#include "boxsim/io/atomic_file.hpp"
#include "boxsim/io/scene.hpp"
#include "boxsim/io/trajectory.hpp"

namespace boxsim::cli {

const char* const kExitStatusHelp =
    "Exit status (docs/cli.md):\n"
    "  0   done\n"
    "  1   the run or the drawing failed (a state not finite, gnuplot, memory)\n"
    "  2   usage: an option or argument missing, unknown, out of range or contradicting another\n"
    "  3   a scene or trajectory file that does not follow its format\n"
    "  66  an input file that does not exist or cannot be read\n"
    "  73  the output cannot be created (no such folder, no permission)\n"
    "  74  reading or writing failed midway (a full disk); nothing is left behind\n";

CommandError::CommandError(const std::string& message, ExitStatus status)
    : CLI::Error("CommandError", message, static_cast<int>(status)) {}

void runGuarded(const std::function<void()>& body) {
  try {
    body();
  } catch (const CLI::Error&) {
    throw;
  } catch (const SceneError& e) {
    throw CommandError(e.what(), ExitStatus::BadInput);
  } catch (const TrajectoryFormatError& e) {
    throw CommandError(e.what(), ExitStatus::BadInput);
  } catch (const CannotCreateError& e) {
    throw CommandError(e.what(), ExitStatus::CannotCreate);
  } catch (const WriteError& e) {
    throw CommandError(e.what(), ExitStatus::IoError);
  } catch (const std::logic_error& e) {
    throw CommandError(e.what(), ExitStatus::Usage);
  } catch (const std::bad_alloc&) {
    throw CommandError("out of memory", ExitStatus::Failure);
  } catch (const std::exception& e) {
    throw CommandError(e.what(), ExitStatus::Failure);
  }
}

namespace {

bool isUsageError(const CLI::Error& e) {
  const auto* command = dynamic_cast<const CommandError*>(&e);
  return command == nullptr || command->get_exit_code() == static_cast<int>(ExitStatus::Usage);
}

/// "boxsim COMMAND: error: MESSAGE", and for a usage error where to read about the options.
std::string failureMessage(const CLI::App* app, const CLI::Error& e) {
  std::string command = "boxsim";
  for (const CLI::App* sub : app->get_subcommands()) command += " " + sub->get_name();
  std::string text = command + ": error: " + e.what() + "\n";
  if (isUsageError(e)) text += "Run '" + command + " --help' for the options and exit statuses.\n";
  return text;
}

}  // namespace

void configureExits(CLI::App& app) {
  app.failure_message(failureMessage);
  app.footer(kExitStatusHelp);
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
    sub->footer(kExitStatusHelp);
}

int exitStatusOf(const CLI::App& app, const CLI::Error& error) {
  const int code = app.exit(error);
  if (code == static_cast<int>(ExitStatus::Ok)) return code;
  if (dynamic_cast<const CommandError*>(&error) != nullptr) return code;
  return static_cast<int>(ExitStatus::Usage);
}

}  // namespace boxsim::cli
