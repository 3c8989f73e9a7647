#include <memory>
#include <string>

#include "boxsim/cli/checks.hpp"
#include "boxsim/cli/commands.hpp"
#include "boxsim/cli/exit_status.hpp"
#include "boxsim/cli/remove_on_signal.hpp"
#include "boxsim/io/trajectory.hpp"
#include "boxsim/io/trajectory_file_writer.hpp"

namespace boxsim::cli {

void addFilterOptions(CLI::App& cmd, FilterChoice& choice, bool required) {
  CLI::Option* filter =
      cmd.add_option("--filter", choice.name,
                     "Filter of thesis §5.5 applied to the poses before they are written: box "
                     "(moving mean over 2H+1 frames) or envelope (a stable pose per body, moved "
                     "only when the body leaves an envelope around it)")
          ->check(CLI::IsMember({"box", "envelope"}));
  if (required) filter->required();
  cmd.add_option("--filter-half-width", choice.halfWidth,
                 "Box filter: frames on each side of the centre frame, H >= 0 (default 2, the "
                 "thesis' two neighbours on each side)");
  cmd.add_option("--envelope-radius", choice.radius,
                 "Envelope filter: how far (m, >= 0) a body may move before its displayed pose "
                 "follows (default 5% of each body's smallest half extent)");
  cmd.add_option("--envelope-angle", choice.angle,
                 "Envelope filter: how far (rad, >= 0) a body may turn before its displayed pose "
                 "follows (default: the envelope radius over the body's half diagonal)");
}

namespace {

struct FilterArgs {
  std::string in;
  std::string out;
  FilterChoice choice;
};

/// Streams the input trajectory through the filter into the output, frame by frame.
void filter(const FilterArgs& args) {
  validateFilterChoice(args.choice);
  requireReadableInput(args.in, "trajectory file");
  requireDistinctOutput(args.out, {args.in});
  TrajectoryFileWriter writer(args.out);
  const RemoveOnSignal cleanup(writer.temporaryPath());
  const std::unique_ptr<FrameSink> stage = makeFilterStage(args.choice, writer);
  readTrajectory(args.in, stage ? *stage : writer);
}

}  // namespace

void addFilterCommand(CLI::App& app) {
  auto args = std::make_shared<FilterArgs>();
  CLI::App* cmd = app.add_subcommand(
      "filter", "Filter a recorded trajectory (thesis §5.5) and write the filtered one; frame "
                "count, times and bodies stay, energies and counters are kept as recorded");
  cmd->add_option("trajectory", args->in, "Trajectory file written by `boxsim run`")
      ->required();
  cmd->add_option("--out,-o", args->out, "Filtered trajectory to write (.dat)")->required();
  addFilterOptions(*cmd, args->choice, true);
  cmd->callback([args] { runGuarded([&] { filter(*args); }); });
}

}  // namespace boxsim::cli
