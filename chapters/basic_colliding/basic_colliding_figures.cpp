// Reproduction driver of the basic colliding chapter (thesis §2.1, §3.3.1, §4.3).
//
// Runs the die scene under the basic colliding technique and writes the data of the chapter's
// figures into the output folder; gnuplot scripts in figures/basic_colliding/ and
// `boxsim render` turn them into images. Writes data only, each file whole or not at all.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "boxsim/basic_colliding/basic_colliding.hpp"
#include "boxsim/collision/obb.hpp"
#include "boxsim/io/atomic_file.hpp"
#include "boxsim/io/scene.hpp"
#include "boxsim/io/simulate.hpp"
#include "boxsim/io/trajectory.hpp"

namespace {

using namespace boxsim;

struct RunResult {
  Trajectory trajectory;
  std::vector<StepStats> stats;  // one per frame; frame 0 has none
  SimulateSummary summary;
};

/// A stepper wrapper that keeps the full StepStats of every step (restarts, limits).
class KeepStats final : public Stepper {
 public:
  KeepStats(Stepper& inner, std::vector<StepStats>& out) : inner_(inner), out_(out) {}
  std::string name() const override { return inner_.name(); }
  StepStats step(World& world, double dt) override {
    out_.push_back(inner_.step(world, dt));
    return out_.back();
  }

 private:
  Stepper& inner_;
  std::vector<StepStats>& out_;
};

std::string header(const std::string& title, const std::string& columns, const RunResult& run) {
  std::ostringstream os;
  os << "# " << title << "\n";
  for (const auto& [key, value] : run.trajectory.meta) os << "# " << key << ": " << value << "\n";
  os << "# columns: " << columns << "\n";
  return os.str();
}

RunResult runDie(const std::string& scenePath, double dt, double duration, Integrator integrator) {
  Scene scene = loadScene(scenePath);
  BasicCollidingParams params;
  params.integrator = integrator;
  BasicCollidingStepper stepper(params);
  RunResult run;
  run.stats.emplace_back();
  KeepStats keep(stepper, run.stats);
  Recorder recorder(scene.world, runParameters(stepper, scene.world, scenePath, dt, duration));
  SimulateOptions options;
  options.dt = dt;
  options.duration = duration;
  run.summary = simulate(scene.world, keep, options, recorder);
  run.trajectory = recorder.trajectory();
  return run;
}

int dieIndex(const Trajectory& t) {
  for (std::size_t i = 0; i < t.bodies.size(); ++i)
    if (!t.bodies[i].immovable) return static_cast<int>(i);
  throw std::runtime_error("the die scene has no movable body");
}

double lowestCorner(const Trajectory& t, const TrajectoryFrame& f, int body) {
  const Obb box{f.x[body], f.q[body].toRotationMatrix(), t.bodies[body].halfExtents};
  double lowest = box.corner(0).y();
  for (int k = 1; k < 8; ++k) lowest = std::min(lowest, box.corner(k).y());
  return lowest;
}

/// Height of the die's centre and lowest corner and its energies against time, under the
/// default semi-implicit Euler and under the thesis' forward Euler (same frames).
void figS2_1DieHeightEnergy(const RunResult& semi, const RunResult& forward, const std::string& dir) {
  const int die = dieIndex(semi.trajectory);
  std::string out = header(
      "s2_1_die_height_energy: the die under the basic colliding technique, semi-implicit "
      "Euler (default) and forward Euler (the thesis' integrator)",
      "t_s centre_m lowest_corner_m kinetic_J potential_J total_J "
      "fe_centre_m fe_lowest_corner_m fe_total_J", semi);
  out += "# forward Euler run: integrator forward_euler, otherwise the same parameters\n";
  for (std::size_t k = 0; k < semi.trajectory.frames.size(); ++k) {
    const TrajectoryFrame& f = semi.trajectory.frames[k];
    const TrajectoryFrame& g = forward.trajectory.frames[k];
    char line[320];
    std::snprintf(line, sizeof line, "%.6f %.9g %.9g %.9g %.9g %.9g %.9g %.9g %.9g\n", f.t,
                  f.x[die].y(), lowestCorner(semi.trajectory, f, die), f.kinetic, f.potential,
                  f.kinetic + f.potential, g.x[die].y(), lowestCorner(forward.trajectory, g, die),
                  g.kinetic + g.potential);
    out += line;
  }
  writeFileAtomically(dir + "/s2_1_die_height_energy.dat", out);
}

/// Collision events, bisection steps and restarts per frame, and whether the frame hit the
/// events-per-step limit.
void figS2_1DieEvents(const RunResult& run, const std::string& dir) {
  std::string out = header("s2_1_die_events: work per frame of the basic colliding technique",
                           "t_s events bisections restarts limit_reached cumulative_events", run);
  long cumulative = 0;
  for (std::size_t k = 1; k < run.trajectory.frames.size(); ++k) {
    const StepStats& s = run.stats[k];
    cumulative += s.events;
    char line[160];
    std::snprintf(line, sizeof line, "%.6f %d %d %d %d %ld\n", run.trajectory.frames[k].t,
                  s.events, s.bisections, s.restarts, s.limitReached ? 1 : 0, cumulative);
    out += line;
  }
  writeFileAtomically(dir + "/s2_1_die_events.dat", out);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Writes the data of the basic colliding chapter's figures (thesis §2.1)"};
  std::string scene;
  std::string outDir;
  double dt = 1.0 / 60.0;
  double duration = 12.0;
  app.add_option("--scene", scene, "The die scene (chapters/basic_colliding/scenes/die.json)")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("--out", outDir, "Folder for the .dat files")->required()->check(CLI::ExistingDirectory);
  app.add_option("--dt", dt, "Time step, s")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--duration", duration, "Simulated time, s")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    const RunResult run = runDie(scene, dt, duration, Integrator::SemiImplicitEuler);
    const RunResult forward = runDie(scene, dt, duration, Integrator::ForwardEuler);
    writeTrajectory(outDir + "/s2_1_die_trajectory.dat", run.trajectory);
    figS2_1DieHeightEnergy(run, forward, outDir);
    figS2_1DieEvents(run, outDir);
    std::cout << "basic_colliding: " << run.summary.steps << " steps, " << run.summary.events
              << " collision events, " << run.summary.bisections << " bisection steps, "
              << run.summary.limitedSteps << " steps at the events-per-step limit\n";
  } catch (const std::exception& e) {
    std::cerr << "basic_colliding_figures: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
