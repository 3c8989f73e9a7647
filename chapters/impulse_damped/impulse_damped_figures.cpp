// Reproduction driver of the impulse-based and damped integration chapter (thesis §5.2-§5.4,
// §6.1, Alg. A.2).
//
// Runs the chapter's scenes under the plain impulse-based step ("impulse") and damped
// integration ("damped") and writes the data of the chapter's figures into the output folder:
// kinetic energy against time, a chatter measure per technique, milliseconds per frame, and the
// trajectories that `boxsim render` turns into the frames and animations of Figs. 6.6 and 6.7.
// Writes data only, each file whole or not at all. Timings are measurements of this machine.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <iostream>
#include <memory>

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/collision/separating_axis.hpp"
#include "boxsim/impulse_damped/damped_integration.hpp"
#include "boxsim/impulse_damped/impulse_stepper.hpp"
#include "boxsim/io/atomic_file.hpp"
#include "boxsim/io/scene.hpp"
#include "boxsim/io/scene_builders.hpp"
#include "boxsim/io/simulate.hpp"
#include "boxsim/io/trajectory.hpp"
#include "boxsim/techniques.hpp"
#include "figure_data.hpp"
#include "friction_figures.hpp"

namespace {

using namespace boxsim;

/// A run: its trajectory and the wall time of every step.
struct Run {
  std::string scene;
  std::string method;
  Trajectory trajectory;
  std::vector<double> msPerStep;  // one per frame after the first
  std::vector<std::pair<int, int>> asleep;  // per step: bodies asleep, movable bodies
};

/// Wraps a stepper to time every step (steady clock, ms) and count the bodies asleep.
class TimedStepper final : public Stepper {
 public:
  explicit TimedStepper(Stepper& inner, Run& run) : inner_(inner), run_(run) {}
  std::string name() const override { return inner_.name(); }
  std::map<std::string, std::string> parameters() const override { return inner_.parameters(); }
  StepStats step(World& world, double dt) override {
    const auto start = std::chrono::steady_clock::now();
    const StepStats s = inner_.step(world, dt);
    run_.msPerStep.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    run_.asleep.emplace_back(s.sleeping, world.movableCount());
    return s;
  }

 private:
  Stepper& inner_;
  Run& run_;
};

/// A run of scene (sceneDir/scene.json) under `stepper` for `duration` s at Δt = 1/60 s.
Run runWith(const std::string& sceneDir, const std::string& scene, Stepper& stepper,
            double duration) {
  const std::string path = sceneDir + "/" + scene + ".json";
  Scene s = loadScene(path);
  Run run{scene, stepper.name(), {}, {}, {}};
  TimedStepper timed(stepper, run);
  const double dt = 1.0 / 60.0;
  Recorder recorder(s.world, runParameters(stepper, s.world, path, dt, duration));
  SimulateOptions options;
  options.dt = dt;
  options.duration = duration;
  simulate(s.world, timed, options, recorder);
  run.trajectory = recorder.trajectory();
  std::cout << "impulse_damped: " << scene << " under " << run.method << ": "
            << run.trajectory.frames.size() - 1 << " steps\n";
  return run;
}

Run runScene(const std::string& sceneDir, const std::string& scene, const std::string& method,
             double duration) {
  std::unique_ptr<Stepper> stepper = makeStepper(method);
  Run run = runWith(sceneDir, scene, *stepper, duration);
  run.method = method;
  return run;
}

/// Kinetic energy of every run against time (one column per run, same frames).
void figS5_2KineticEnergy(const std::vector<Run>& runs, const std::string& dir) {
  std::string columns = "t_s";
  for (const Run& r : runs) columns += " " + r.scene + "_" + r.method + "_J";
  std::string out = header("s5_2_kinetic_energy: kinetic energy, plain impulse step and damped integration", columns);
  std::size_t frames = runs.front().trajectory.frames.size();
  for (const Run& r : runs) frames = std::min(frames, r.trajectory.frames.size());
  for (std::size_t k = 0; k < frames; ++k) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.6f", runs.front().trajectory.frames[k].t);
    out += buffer;
    for (const Run& r : runs) {
      std::snprintf(buffer, sizeof buffer, " %.6e", r.trajectory.frames[k].kinetic);
      out += buffer;
    }
    out += "\n";
  }
  writeFileAtomically(dir + "/s5_2_kinetic_energy.dat", out);
}

/// Chatter of a settled run over frames [from, to): the number of sign changes of a body's
/// vertical velocity (from frame differences) whose speed exceeds 1e-4 m/s, summed over
/// bodies and given per body and second; and the largest vertical jitter amplitude (max - min
/// of a body's height over the window).
struct Chatter {
  double signChangesPerBodySecond = 0.0;
  double jitterAmplitude = 0.0;
};

Chatter chatterOf(const Trajectory& t, std::size_t from, std::size_t to) {
  Chatter c;
  long changes = 0;
  int bodies = 0;
  const double dt = t.frames[1].t - t.frames[0].t;
  for (std::size_t b = 0; b < t.bodies.size(); ++b) {
    if (t.bodies[b].immovable) continue;
    ++bodies;
    double lo = t.frames[from].x[b].y(), hi = lo, previous = 0.0;
    for (std::size_t k = from + 1; k < to; ++k) {
      const double y = t.frames[k].x[b].y();
      lo = std::min(lo, y);
      hi = std::max(hi, y);
      const double v = (y - t.frames[k - 1].x[b].y()) / dt;
      if (std::abs(v) > 1e-4) {
        if (previous != 0.0 && (v > 0.0) != (previous > 0.0)) ++changes;
        previous = v;
      }
    }
    c.jitterAmplitude = std::max(c.jitterAmplitude, hi - lo);
  }
  const double seconds = static_cast<double>(to - from) * dt;
  c.signChangesPerBodySecond = static_cast<double>(changes) / (bodies * seconds);
  return c;
}

/// The settled window of a scene of the chatter figures, s: die 6-8 s, tower 2-8 s, the
/// pyramid 2-5 s (before the shot).
std::pair<double, double> settledWindow(const std::string& scene) {
  return {scene == "die" ? 6.0 : 2.0, scene == "pyramid10_shot" ? 5.0 : 8.0};
}

/// The chatter measure for each run, over a window where the scene should be at rest.
void figS5_2Chatter(const std::vector<Run>& runs, const std::string& dir) {
  std::string out = header("s5_2_chatter: chatter of settled scenes (window: die 6-8 s, tower 2-8 s, pyramid 2-5 s)",
                           "case label sign_changes_per_body_s jitter_amplitude_m");
  int index = 0;
  for (const Run& r : runs) {
    const auto [from, to] = settledWindow(r.scene);
    const Chatter c = chatterOf(r.trajectory, static_cast<std::size_t>(from * 60), static_cast<std::size_t>(to * 60));
    char line[200];
    std::snprintf(line, sizeof line, "%d %s/%s %.6g %.6g\n", index++, r.scene.c_str(), r.method.c_str(),
                  c.signChangesPerBodySecond, c.jitterAmplitude);
    out += line;
  }
  writeFileAtomically(dir + "/s5_2_chatter.dat", out);
}

/// Damped integration with one of its techniques off at a time (issue: which of them stops the
/// chatter), and the plain impulse step beside it: the chatter measures and the mean kinetic
/// energy over each scene's settled window. The kinetic energy catches what the positions do
/// not: a body whose momenta never settle while DAMPENOBJECTS L23-L28's snap holds its pose.
void figS5_3Ablation(const std::string& sceneDir, const std::string& dir) {
  struct Variant {
    const char* name;
    std::function<void(DampedIntegrationParams&)> change;  ///< none: the plain impulse step
  };
  const std::vector<Variant> variants = {
      {"damped", [](DampedIntegrationParams&) {}},
      {"no_damping", [](DampedIntegrationParams& p) { p.damp = false; }},
      {"no_fix_contacts", [](DampedIntegrationParams& p) { p.fixContactConstraints = false; }},
      {"no_geometric_stability", [](DampedIntegrationParams& p) { p.useGeometricStability = false; }},
      {"no_sleeping", [](DampedIntegrationParams& p) { p.sleep.enabled = false; }},
      {"every_pass", [](DampedIntegrationParams& p) {
         p.impulse.gathering = ContactGatheringMode::EveryPass;
       }},
      {"plain_impulse", nullptr},
  };
  std::string out = header(
      "s5_3_ablation: damped integration with one technique off at a time, and the plain impulse "
      "step (windows: die 6-8 s, tower 2-8 s, pyramid 2-5 s)",
      "case scene variant sign_changes_per_body_s jitter_amplitude_m mean_kinetic_J");
  int index = 0;
  for (const char* scene : {"die", "tower10", "pyramid10_shot"}) {
    const auto [from, to] = settledWindow(scene);
    for (const Variant& v : variants) {
      const std::string path = sceneDir + "/" + scene + ".json";
      Scene s = loadScene(path);
      std::unique_ptr<Stepper> stepper;
      if (v.change) {
        DampedIntegrationParams params;
        v.change(params);
        stepper = std::make_unique<DampedIntegrationStepper>(params);
      } else {
        stepper = std::make_unique<ImpulseStepper>();
      }
      Recorder recorder(s.world, runParameters(*stepper, s.world, path, 1.0 / 60.0, to));
      SimulateOptions options;
      options.duration = to;
      simulate(s.world, *stepper, options, recorder);
      const Trajectory& t = recorder.trajectory();
      const auto first = static_cast<std::size_t>(from * 60), last = static_cast<std::size_t>(to * 60);
      const Chatter c = chatterOf(t, first, last);
      double kinetic = 0.0;
      for (std::size_t k = first; k < last; ++k) kinetic += t.frames[k].kinetic;
      kinetic /= static_cast<double>(last - first);
      char line[256];
      std::snprintf(line, sizeof line, "%d %s %s %.6g %.6g %.6g\n", index++, scene, v.name,
                    c.signChangesPerBodySecond, c.jitterAmplitude, kinetic);
      out += line;
    }
  }
  writeFileAtomically(dir + "/s5_3_ablation.dat", out);
}

/// Milliseconds per frame against time for the timed runs.
void figS6_1MsPerFrame(const std::vector<Run>& runs, const std::string& dir) {
  std::string columns = "t_s";
  for (const Run& r : runs) columns += " " + r.scene + "_" + r.method + "_ms";
  std::string out = header("s6_1_ms_per_frame: wall time per 1/60 s step on this machine, one thread", columns);
  std::size_t steps = runs.front().msPerStep.size();
  for (const Run& r : runs) steps = std::min(steps, r.msPerStep.size());
  for (std::size_t k = 0; k < steps; ++k) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.6f", (k + 1) / 60.0);
    out += buffer;
    for (const Run& r : runs) {
      std::snprintf(buffer, sizeof buffer, " %.4f", r.msPerStep[k]);
      out += buffer;
    }
    out += "\n";
  }
  writeFileAtomically(dir + "/s6_1_ms_per_frame.dat", out);
}

/// The three contact normal models of §3.3.2 compared: for each, under the plain impulse step
/// and under damped integration, the base-10 pyramid before the shot (0-5 s: chatter, apex
/// sag, deepest penetration) and the die (time from which its momenta stay exactly zero).
void figS3_3ContactNormals(const std::string& sceneDir, const std::string& dir) {
  std::string out = header("s3_3_contact_normals: contact normal models (thesis §3.3.2 and footnote)",
                           "case label pyramid_sign_changes_per_body_s pyramid_apex_sag_m "
                           "pyramid_deepest_penetration_m die_rest_s");
  int index = 0;
  for (const char* method : {"impulse", "damped"}) {
    for (ContactNormalModel model : {ContactNormalModel::SeparatingAxis,
                                     ContactNormalModel::PreviousClosestFace,
                                     ContactNormalModel::SignedDistance}) {
      const auto makeOne = [&]() -> std::unique_ptr<Stepper> {
        if (std::string(method) == "impulse") {
          ImpulseStepperParams p;
          p.impulse.normalModel = model;
          return std::make_unique<ImpulseStepper>(p);
        }
        DampedIntegrationParams p;
        p.impulse.normalModel = model;
        return std::make_unique<DampedIntegrationStepper>(p);
      };
      // The pyramid, 5 s before the shot.
      Scene pyramid = loadScene(sceneDir + "/pyramid10_shot.json");
      std::unique_ptr<Stepper> stepper = makeOne();
      // Scenes list their bodies before their builders: the apex is the last body.
      const int apex = static_cast<int>(pyramid.world.bodies.size()) - 1;
      const double apex0 = pyramid.world.bodies[apex].s.x.y();
      Recorder recorder(pyramid.world, {});
      recorder.capture(pyramid.world, 0.0);
      double sag = 0.0, deepest = 0.0;
      for (int k = 1; k <= 300; ++k) {
        stepper->step(pyramid.world, 1.0 / 60.0);
        recorder.capture(pyramid.world, k / 60.0);
        sag = std::max(sag, apex0 - pyramid.world.bodies[apex].s.x.y());
        deepest = std::max(deepest, deepestPenetration(pyramid.world));
      }
      const Chatter c = chatterOf(recorder.trajectory(), 60, 300);
      // The die: the first step from which its momenta stay exactly zero (to 8 s), or -1.
      Scene die = loadScene(sceneDir + "/die.json");
      stepper = makeOne();
      int restStep = -1;
      for (int k = 1; k <= 480; ++k) {
        stepper->step(die.world, 1.0 / 60.0);
        const RigidBody& b = die.world.bodies[1];
        const bool still = b.s.P == Vec3::Zero() && b.s.L == Vec3::Zero();
        restStep = still ? (restStep < 0 ? k : restStep) : -1;
      }
      char line[256];
      std::snprintf(line, sizeof line, "%d %s/%s %.6g %.6g %.6g %.6g\n", index++, method,
                    contactNormalModelName(model).c_str(), c.signChangesPerBodySecond, sag, deepest,
                    restStep < 0 ? -1.0 : restStep / 60.0);
      out += line;
    }
  }
  writeFileAtomically(dir + "/s3_3_contact_normals.dat", out);
}

/// The clump of 100 under damped integration with dampCollidingBodies on, 25 s: it settles.
Trajectory clumpDampingCollisions(const std::string& sceneDir) {
  const std::string path = sceneDir + "/clump100.json";
  Scene scene = loadScene(path);
  DampedIntegrationParams params;
  params.dampCollidingBodies = true;
  DampedIntegrationStepper stepper(params);
  Recorder recorder(scene.world, runParameters(stepper, scene.world, path, 1.0 / 60.0, 25.0));
  SimulateOptions options;
  options.duration = 25.0;
  simulate(scene.world, stepper, options, recorder);
  return recorder.trajectory();
}

}  // namespace

/// Chatter detected from history (\thesis{§6.3.1}; SleepParams::chatterDetection) against
/// sleeping as it is, on the die, the shot pyramid, the settling pile and the clump on the
/// ground: when every body is asleep for good (s; -1 if not by the end), the mean kinetic energy
/// of the last 2 s, the mean ms a step (one thread, this machine) and the bodies asleep at the end.
void figS6_3ChatterHistory(const std::string& sceneDir, const std::string& dir) {
  std::string out = header(
      "s6_3_chatter_history: damped integration, sleeping as it is (detection off) and with chatter "
      "detected from history (on)",
      "case scene detection duration_s at_rest_from_s residual_kinetic_J ms_per_step asleep movable");
  int index = 0;
  const std::pair<const char*, double> scenes[] = {
      {"die", 8.0}, {"pyramid10_shot", 8.0}, {"pile343", 30.0}, {"clump100_ground", 20.0}};
  for (const auto& [scene, duration] : scenes) {
    for (const bool detection : {false, true}) {
      DampedIntegrationParams params;
      params.sleep.chatterDetection = detection;
      DampedIntegrationStepper stepper(params);
      const Run run = runWith(sceneDir, scene, stepper, duration);
      const double dt = 1.0 / 60.0;
      const std::size_t steps = run.asleep.size(), tail = static_cast<std::size_t>(std::lround(2.0 / dt));
      // The step from which every movable body stays asleep to the end, if any.
      std::size_t restFrom = steps;
      while (restFrom > 0 && run.asleep[restFrom - 1].first == run.asleep[restFrom - 1].second) --restFrom;
      double kinetic = 0.0, ms = 0.0;
      for (std::size_t k = steps - tail + 1; k <= steps; ++k)
        kinetic += run.trajectory.frames[k].kinetic / static_cast<double>(tail);
      for (const double m : run.msPerStep) ms += m;
      const auto [asleep, movable] = run.asleep.back();
      char line[256];
      std::snprintf(line, sizeof line, "%d %s %s %g %.4g %.6g %.6g %d %d\n", index++, scene,
                    detection ? "on" : "off", duration,
                    restFrom == steps ? -1.0 : static_cast<double>(restFrom + 1) * dt,
                    kinetic, ms / static_cast<double>(steps), asleep, movable);
      out += line;
      std::cout << "impulse_damped: " << scene << " with chatter detection " << (detection ? "on" : "off")
                << ": " << line;
    }
  }
  writeFileAtomically(dir + "/s6_3_chatter_history.dat", out);
}

int main(int argc, char** argv) {
  CLI::App app{"Writes the data of the impulse-based and damped integration chapter's figures"};
  std::string sceneDir;
  std::string outDir;
  double clumpSeconds = 8.0;
  app.add_option("--scenes", sceneDir, "chapters/impulse_damped/scenes")->required()->check(CLI::ExistingDirectory);
  app.add_option("--out", outDir, "Folder for the .dat files")->required()->check(CLI::ExistingDirectory);
  app.add_option("--clump-seconds", clumpSeconds, "Simulated time of the 1000-cube clump, s")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    std::vector<Run> energy;
    for (const char* scene : {"die", "tower10", "pyramid10_shot"})
      for (const char* method : {"impulse", "damped"}) energy.push_back(runScene(sceneDir, scene, method, 8.0));
    figS5_2KineticEnergy(energy, outDir);
    figS5_2Chatter(energy, outDir);
    for (const Run& r : energy)
      if (r.scene == "pyramid10_shot") writeTrajectory(outDir + "/fig6_6_pyramid10_" + r.method + ".dat", r.trajectory);
    figS3_3ContactNormals(sceneDir, outDir);
    figS5_3Ablation(sceneDir, outDir);
    figFig5_2DampingVsFriction(outDir);
    figS7FrictionIncline(outDir);
    figS7FrictionInclineSweep(outDir);
    figS6_3ChatterHistory(sceneDir, outDir);
    std::vector<Run> timed;
    timed.push_back(runScene(sceneDir, "pyramid20_shot", "damped", 8.0));
    timed.push_back(runScene(sceneDir, "clump100", "damped", 8.0));
    timed.push_back(runScene(sceneDir, "clump1000", "damped", clumpSeconds));
    figS6_1MsPerFrame(timed, outDir);
    writeTrajectory(outDir + "/fig6_6_pyramid20_damped.dat", timed[0].trajectory);
    writeTrajectory(outDir + "/fig6_7_clump100_damped.dat", timed[1].trajectory);
    writeTrajectory(outDir + "/fig6_7_clump1000_damped.dat", timed[2].trajectory);
    writeTrajectory(outDir + "/fig6_7_clump100_damped_colliding.dat", clumpDampingCollisions(sceneDir));
    // Fig. 6.7 read with the origin on the ground: the cubes pile up and settle.
    writeTrajectory(outDir + "/fig6_7_clump100_ground_damped.dat",
                    runScene(sceneDir, "clump100_ground", "damped", 15.0).trajectory);
  } catch (const std::exception& e) {
    std::cerr << "impulse_damped_figures: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
