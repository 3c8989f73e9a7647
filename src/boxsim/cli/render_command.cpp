#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "boxsim/cli/checks.hpp"
#include "boxsim/cli/commands.hpp"
#include "boxsim/cli/exit_status.hpp"
#include "boxsim/io/render.hpp"
#include "boxsim/io/trajectory.hpp"

namespace boxsim::cli {

namespace {
struct RenderArgs {
  std::string trajectory;
  std::string out;
  std::vector<int> frames;
  int width = 800;
  int height = 600;
  std::vector<std::string> colours;
};

/// "NAME=RRGGBB" (a leading # allowed) as a body name and 0xRRGGBB.
std::pair<std::string, int> parseBodyColour(const std::string& text) {
  const std::size_t eq = text.rfind('=');
  std::string hex = eq == std::string::npos ? "" : text.substr(eq + 1);
  if (!hex.empty() && hex[0] == '#') hex.erase(0, 1);
  const bool valid = eq != std::string::npos && eq > 0 && hex.size() == 6 &&
                     hex.find_first_not_of("0123456789abcdefABCDEF") == std::string::npos;
  if (!valid)
    throw std::invalid_argument("--colour '" + text +
                                "': expected NAME=RRGGBB, a body name and six hex digits, "
                                "such as die=d62728");
  return {text.substr(0, eq), std::stoi(hex, nullptr, 16)};
}

}  // namespace

void addRenderCommand(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand(
      "render", "Draw a trajectory in 3D with gnuplot: a frame (PNG, SVG), a strip of frames "
                "(PNG with several --frame), or the whole run animated (GIF)");
  cmd->add_option("trajectory", args->trajectory, "Trajectory file written by `boxsim run`")
      ->required();
  cmd->add_option("--out,-o", args->out, "Image to write: FILE.png, FILE.svg or FILE.gif")
      ->required();
  cmd->add_option("--frame,-f", args->frames,
                  "Frame index to draw (repeat for a strip); default: frame 0, or all for a GIF");
  cmd->add_option("--width", args->width, "Image width, pixels")->capture_default_str()
      ->check(CLI::Range(64, 8192));
  cmd->add_option("--height", args->height, "Image height, pixels")->capture_default_str()
      ->check(CLI::Range(64, 8192));
  cmd->add_option("--colour", args->colours,
                  "Fill colour of a body, NAME=RRGGBB (repeat for several bodies); the others "
                  "keep the palette");
  cmd->callback([args] {
    runGuarded([&] {
      requireReadableInput(args->trajectory, "trajectory file");
      requireDistinctOutput(args->out, {args->trajectory});
      const Trajectory trajectory = readTrajectory(args->trajectory);
      RenderOptions options;
      options.width = args->width;
      options.height = args->height;
      options.frames = args->frames;
      for (const std::string& c : args->colours) options.bodyColours.insert(parseBodyColour(c));
      renderTrajectory(trajectory, args->out, options);
    });
  });
}

}  // namespace boxsim::cli
