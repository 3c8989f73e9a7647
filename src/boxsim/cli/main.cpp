// The `boxsim` command: runs scenes under any technique, filters and renders trajectories.
// Exit statuses: cli/exit_status.hpp, docs/cli.md.
#include <exception>
#include <iostream>

#include "boxsim/cli/commands.hpp"
#include "boxsim/cli/exit_status.hpp"

int main(int argc, char** argv) {
  CLI::App app{
      "boxsim: techniques for real-time rigid body simulation of boxes (Egan 2003).\n"
      "Run a scene under a technique, then render the trajectory it wrote."};
  app.require_subcommand(1);
  boxsim::cli::addRunCommand(app);
  boxsim::cli::addRenderCommand(app);
  boxsim::cli::addFilterCommand(app);
  boxsim::cli::configureExits(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::Error& e) {
    return boxsim::cli::exitStatusOf(app, e);
  } catch (const std::exception& e) {
    std::cerr << "boxsim: error: " << e.what() << "\n";
    return static_cast<int>(boxsim::cli::ExitStatus::Failure);
  }
  return 0;
}
