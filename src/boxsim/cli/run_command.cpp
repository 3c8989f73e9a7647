#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

#include "boxsim/cli/checks.hpp"
#include "boxsim/cli/commands.hpp"
#include "boxsim/cli/exit_status.hpp"
#include "boxsim/cli/remove_on_signal.hpp"
#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/io/scene.hpp"
#include "boxsim/io/simulate.hpp"
#include "boxsim/io/trajectory_file_writer.hpp"
#include "boxsim/techniques.hpp"

namespace boxsim::cli {

namespace {

struct RunArgs {
  std::string scene;
  std::string method = "damped";  // damped integration, the thesis' contribution (§5.2)
  std::string integrator;  // empty: the method's default
  std::string contactNormal;  // empty: the method's default
  std::string contactGathering;  // empty: the method's default
  std::string geometricStability;  // off, thesis, under_load or empty (the method's default)
  // Switches given as on or off (CLI11 reads them as booleans); empty: the method's default.
  std::optional<bool> sleep;
  std::optional<bool> chatterDetection;
  std::optional<bool> dampSupportedOnly;
  std::optional<bool> fixStopApproach;
  std::optional<bool> continuousCollision;
  std::optional<bool> predictedAnchor;
  std::optional<bool> exactEdgePairs;
  std::optional<bool> edgeCorners;
  std::optional<int> impactPasses;  // empty: the method's default (0)
  std::optional<int> shockIterations;  // empty: the method's default (8)
  std::string broadPhase;     // empty: the scene's choice
  std::optional<unsigned long> plausibilitySeed;
  std::optional<int> threads;  // empty: the method's default (1)
  double dt = 1.0 / 60.0;
  double duration = 5.0;
  std::string out;            // empty: <scene stem>.dat in the working directory
  bool quiet = false;
  FilterChoice filter;  // thesis §5.5; empty name: the raw trajectory is written
};

/// A one-line progress bar on stderr, drawn only once the run has taken over a second, and
/// only when enabled (run_command enables it for a terminal: redrawn with '\r', it would
/// litter a file or a pipe).
class ProgressBar {
 public:
  explicit ProgressBar(bool enabled) : enabled_(enabled), start_(Clock::now()) {}
  void update(double fraction) {
    if (!enabled_) return;
    const Clock::time_point now = Clock::now();
    if (now - start_ < std::chrono::seconds(1) || now - last_ < std::chrono::milliseconds(100))
      return;
    last_ = now;
    draw(fraction, now);
  }
  /// Draws the full bar once more (if it was shown at all) and ends its line.
  void finish() {
    if (!drawn_) return;
    draw(1.0, Clock::now());
    std::fprintf(stderr, "\n");
  }

 private:
  using Clock = std::chrono::steady_clock;
  bool enabled_;
  bool drawn_ = false;
  Clock::time_point start_;
  Clock::time_point last_{};

  void draw(double fraction, Clock::time_point now) {
    drawn_ = true;
    const int width = 40;
    const int filled = static_cast<int>(fraction * width + 0.5);
    std::fprintf(stderr, "\r[%s%s] %3d%% %6.1f s", std::string(filled, '#').c_str(),
                 std::string(width - filled, '.').c_str(), static_cast<int>(fraction * 100 + 0.5),
                 std::chrono::duration<double>(now - start_).count());
    std::fflush(stderr);
  }
};

TechniqueOptions techniqueOptions(const RunArgs& args) {
  TechniqueOptions options;
  if (!args.integrator.empty()) options.integrator = parseIntegrator(args.integrator);
  if (!args.contactNormal.empty()) options.contactNormal = parseContactNormalModel(args.contactNormal);
  if (!args.contactGathering.empty())
    options.contactGathering = parseContactGathering(args.contactGathering);
  if (!args.geometricStability.empty())
    options.geometricStability = parseGeometricStabilityMode(args.geometricStability);
  options.sleep = args.sleep;
  options.chatterDetection = args.chatterDetection;
  options.dampSupportedOnly = args.dampSupportedOnly;
  options.fixStopApproach = args.fixStopApproach;
  options.continuousCollision = args.continuousCollision;
  options.predictedAnchor = args.predictedAnchor;
  options.exactEdgePairs = args.exactEdgePairs;
  options.edgeCorners = args.edgeCorners;
  options.impactPasses = args.impactPasses;
  options.shockIterations = args.shockIterations;
  options.plausibilitySeed = args.plausibilitySeed;
  options.threads = args.threads;
  return options;
}

/// --out, or else the scene's file name with .dat in the working directory.
std::string outputPath(const RunArgs& args) {
  if (!args.out.empty()) return args.out;
  return std::filesystem::path(args.scene).stem().string() + ".dat";
}

/// The summary line (unless quiet) and the warning of a run that met its method's work limit.
void report(const SimulateSummary& summary, const Stepper& stepper, const std::string& out,
            bool quiet) {
  if (!quiet)
    std::cerr << "boxsim run: " << summary.steps << " steps, " << summary.events
              << (summary.bisections > 0
                      ? " collision events, " + std::to_string(summary.bisections) + " bisection steps"
                      : " impulses")
              << " -> " << out << "\n";
  if (summary.limitedSteps > 0)
    std::cerr << "boxsim run: warning: " << summary.limitedSteps << " of " << summary.steps
              << " steps hit the work limit of the '" << stepper.name()
              << "' method and dropped the rest of their time step: " << stepper.workLimit()
              << "\n";
}

void run(const RunArgs& args) {
  // Everything that can be checked is checked before the run, the output path included.
  const std::unique_ptr<Stepper> stepper = makeStepper(args.method, techniqueOptions(args));
  checkedStepCount(args.dt, args.duration);
  validateFilterChoice(args.filter);
  const std::string out = outputPath(args);
  requireReadableInput(args.scene, "scene file");
  requireDistinctOutput(out, {args.scene});
  TrajectoryFileWriter writer(out);  // makes the temporary file beside `out` now
  const RemoveOnSignal cleanup(writer.temporaryPath());
  Scene scene = loadScene(args.scene);
  if (!args.broadPhase.empty()) scene.world.broadPhase = parseBroadPhase(args.broadPhase);
  try {
    requireFrictionModel(scene.world, *stepper);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(args.scene + ": " + e.what());
  }

  // Frames stream through the filter (if any) into the temporary file, renamed at the end.
  const std::unique_ptr<FrameSink> filter = makeFilterStage(args.filter, writer);
  FrameSink& sink = filter ? *filter : writer;
  Recorder recorder(scene.world,
                    runParameters(*stepper, scene.world, args.scene, args.dt, args.duration), sink);
  ProgressBar bar(!args.quiet && ::isatty(STDERR_FILENO) == 1);
  SimulateOptions options;
  options.dt = args.dt;
  options.duration = args.duration;
  options.progress = [&bar](double f) { bar.update(f); };
  const SimulateSummary summary = simulate(scene.world, *stepper, options, recorder);
  bar.finish();
  sink.finish();
  report(summary, *stepper, out, args.quiet);
}

}  // namespace

void addRunCommand(CLI::App& app) {
  auto args = std::make_shared<RunArgs>();
  CLI::App* cmd = app.add_subcommand(
      "run", "Run a scene under a technique and write its trajectory (frame by frame into a "
             "temporary file beside the output, renamed over it at the end)");
  cmd->add_option("scene", args->scene, "Scene file (JSON; see docs/scene_format.md)")
      ->required();
  std::string methods;
  for (const std::string& m : methodNames()) methods += (methods.empty() ? "" : ", ") + m;
  cmd->add_option("--method,-m", args->method,
                  "Technique: " + methods +
                      " (default damped: damped integration, thesis §5.2, the thesis' own "
                      "technique; basic_colliding is the naive baseline of §2.1)")
      ->capture_default_str();
  cmd->add_option("--integrator", args->integrator,
                  "Integrator between collisions: forward_euler, semi_implicit_euler, "
                  "runge_kutta_4, split_rotation (basic_colliding, analytic and the timewarps); "
                  "of the last position update: semi_implicit_euler, split_rotation (impulse, "
                  "damped). Default: semi_implicit_euler");
  cmd->add_option("--contact-normal", args->contactNormal,
                  "Contact normal model of impulse and damped: separating_axis, "
                  "previous_closest_face (default), signed_distance")
      ->check(CLI::IsMember({"separating_axis", "previous_closest_face", "signed_distance"}));
  cmd->add_option("--contact-gathering", args->contactGathering,
                  "How impulse and damped find contacts at predicted positions: once_per_step "
                  "(default, one narrow phase per step, first-order prediction), every_pass "
                  "(Alg. A.2 as written)")
      ->check(CLI::IsMember({"once_per_step", "every_pass"}));
  cmd->add_option("--predicted-anchor", args->predictedAnchor,
                  "Once-per-step gathering of impulse and damped: find the contacts of bodies "
                  "fast at a step's start where its first pass predicts them, and predict the "
                  "passes from there, so that a body whose velocity the passes barely change "
                  "costs no narrow phase per pass: on, off (default, from the current poses)")
      ->check(CLI::IsMember({"on", "off"}));
  cmd->add_option("--exact-edge-pairs", args->exactEdgePairs,
                  "Once-per-step gathering of impulse and damped: gather a pair that touches "
                  "edge to edge at the step's start exactly in every pass instead of predicting "
                  "its points (a small turn brings another corner into contact): on, off "
                  "(default)")
      ->check(CLI::IsMember({"on", "off"}));
  cmd->add_option("--edge-corners", args->edgeCorners,
                  "Once-per-step gathering of impulse and damped: a pair that touches edge to "
                  "edge at the step's start also keeps the corners of its best face, predicted "
                  "in every pass as its point is, so that the corners a small turn brings "
                  "down are not missed: on, off (default)")
      ->check(CLI::IsMember({"on", "off"}));
  cmd->add_option("--geometric-stability", args->geometricStability,
                  "Bodies that gravity and frictionless contact cannot move (analytic: left out "
                  "of the contact forces; damped: COLLIDE L11-L14): off, thesis (§5.4's rule), "
                  "under_load (also boxes held by the loads they carry, §6.3.1 Figs. 6.4-6.5). "
                  "Default: off for analytic, thesis for damped")
      ->check(CLI::IsMember({"off", "thesis", "under_load"}));
  cmd->add_option("--sleep", args->sleep, "Sleeping of bodies at rest (damped): on (default), off")
      ->check(CLI::IsMember({"on", "off"}));
  cmd->add_option("--chatter-detection", args->chatterDetection,
                  "Chatter detected from history (damped, thesis §6.3.1): a supported body whose "
                  "pose stays within 5% of its size for the time to sleep, its energy not "
                  "growing, falls asleep: on, off (default)")
      ->check(CLI::IsMember({"on", "off"}));
  cmd->add_option("--damp-supported-only", args->dampSupportedOnly,
                  "DAMPENOBJECTS damps only bodies whose contacts reach down to the ground or "
                  "another immovable body (damped): on, off (default: the thesis' rule, every "
                  "body in contact, which slows boxes touching in free fall)")
      ->check(CLI::IsMember({"on", "off"}));
  cmd->add_option("--fix-stop-approach", args->fixStopApproach,
                  "FIXCONTACTCONSTRAINTS also stops the approach of a frictional body it lifts "
                  "out of more than four times a step's fall from rest (damped): on (default; "
                  "a tall frictional column that lands at once no longer gains energy), off "
                  "(positions alone, as the thesis)")
      ->check(CLI::IsMember({"on", "off"}));
  cmd->add_option("--continuous-collision", args->continuousCollision,
                  "Continuous collision detection for fast bodies (damped): on, off (default)")
      ->check(CLI::IsMember({"on", "off"}));
  cmd->add_option("--impact-passes", args->impactPasses,
                  "Collision passes damped integration may add after its five while the pass "
                  "before still stopped an impact (a pair approaching faster than 0.05 of its "
                  "smaller box's half size a step), so that a landing stops a whole column of "
                  "boxes in its step (default 0: the thesis' five)")
      ->check(CLI::Range(0, 1000));
  cmd->add_option("--shock-iterations", args->shockIterations,
                  "With friction, how many times damped integration's shock sweep may visit a "
                  "level's contacts, their impulses accumulated, until a visit changes nothing "
                  "(default 8; 1: each contact once, which lifts a body resting on several "
                  "supports)")
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--broad-phase", args->broadPhase,
                  "How candidate pairs are found, overriding the scene's \"broad_phase\": "
                  "sweep_and_prune (default) or all_pairs (every pair tested, thesis §4.1); the "
                  "same pairs either way, so the same trajectory")
      ->check(CLI::IsMember({broadPhaseName(BroadPhase::AllPairs),
                             broadPhaseName(BroadPhase::SweepAndPrune)}));
  cmd->add_option("--plausibility-seed", args->plausibilitySeed,
                  "Turn on the random perturbation of fast collisions (damped, thesis §4.2) "
                  "with this seed; the seed is written into the output header");
  cmd->add_option("--threads", args->threads,
                  "Threads of the passes (impulse, damped; default 1): COLLIDE's contacts in "
                  "dependency levels of the thesis' own order, the fast pairs' narrow phases "
                  "each into its own slot, so the trajectory is the same bit for bit for any "
                  "number; written into the output header")
      ->check(CLI::Range(1, 1024));
  cmd->add_option("--dt", args->dt, "Time step, s")
      ->default_str(shortestText(args->dt))
      ->check(finiteNumber(0.0, false, "s"));
  cmd->add_option("--duration,-t", args->duration,
                  "Simulated time, s: a whole number of time steps, so that every step is dt "
                  "long and the run ends at the duration")
      ->capture_default_str()
      ->check(finiteNumber(0.0, true, "s"));
  cmd->add_option("--out,-o", args->out,
                  "Trajectory file to write (.dat, gnuplot columns); default: the scene's file "
                  "name with .dat, in the working directory");
  cmd->add_flag("--quiet,-q", args->quiet,
                "No progress bar and no summary (the bar is drawn only on a terminal anyway)");
  addFilterOptions(*cmd, args->filter, false);
  cmd->callback([args] { runGuarded([&] { run(*args); }); });
}

}  // namespace boxsim::cli
