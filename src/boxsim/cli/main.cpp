// The `boxsim` command: runs scenes under any technique and renders trajectories.
#include <iostream>

#include "boxsim/cli/commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{
      "boxsim: techniques for real-time rigid body simulation of boxes (Egan 2003).\n"
      "Run a scene under a technique, then render the trajectory it wrote."};
  app.require_subcommand(1);
  boxsim::cli::addRunCommand(app);
  boxsim::cli::addRenderCommand(app);
  boxsim::cli::addFilterCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::cerr << "boxsim: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
