/// \file
/// Milliseconds per step of the impulse-based techniques (\thesis{§5.2}, \alg{A.2}) on the
/// scenes of chapters/impulse_damped/scenes/, each timed in a representative state.
///
/// Run it with `cmake --build build --target bench` (or the `bench` workflow preset): the table
/// goes to the console, the same numbers as JSON to build/bench/step_bench.json. To time one
/// case: `build/bench/boxsim_bench --benchmark_filter=pyramid20`.
///
/// Reading the table: every case repeats its measurement a few times and prints only the
/// aggregates. "Time" is wall-clock milliseconds per step (the `_median` row is the number to
/// quote), "CPU" the same in process CPU time; `contacts` and `sleeping` are per-step averages
/// of StepStats over the timed steps; damped integration's cases add the ms per step of each
/// stage of \alg{A.2} (DampedStepProfile: ms_start the contacts at the step's start, ms_collide
/// and ms_contact the passes, ms_shock the friction's shock propagation sweep, ms_damp gravity
/// and DAMPENOBJECTS, ms_fix FIXCONTACTCONSTRAINTS,
/// ms_stable SETGEOMETRICALLYSTABLE, ms_sleep sleeping) and the separating-axis tests per step
/// (sat; of those sat_pass the passes', sat_start the step's start's, sat_fix those of
/// FIXCONTACTCONSTRAINTS with its contacts found again; axis_checks the one-axis checks that
/// answered for a test, separatedBeyond, not among the tests). A label states the target the project set
/// for that case.
/// The `_cv` row is the spread between repetitions: above a few percent, something else was
/// using the machine and the numbers are indicative only. "Library was built as DEBUG" is about
/// Debian's build of Google Benchmark itself; boxsim is timed as configured (Release).
///
/// Names: BM_DampedStep/<scene>_awake runs damped integration with sleeping off (\alg{A.2} as
/// written); <scene>_sleeping runs it with sleeping on (\thesis{§4.5}, the default);
/// BM_ImpulseStep/<scene> runs Guendelman et al.'s plain impulse step ("impulse"). A pyramid
/// case times the settled pyramid just before the shot, with the projectile still parked;
/// pyramid20_hit times the half second in which the projectile strikes it. The clump's cost
/// changes several-fold over its run: clump1000 times the second after 3 s, when the cubes have
/// flown apart and are landing, clump1000_collide the half second after 1.5 s, when they meet in
/// mid-air. The dense piles at restitution 0: pile343_settling times the second after 1 s of the
/// settling heap, clump1000_e0_pile the second after 2 s of the 1000-cube clump at e = 0, when
/// it piles up on the ground; pile343_settling_e09 is the heap at e = 0.9. The 10 000-cube
/// clump of bench/peers, at e = 0.9 and 0, times ten steps from 1.5 s, when its lowest layers
/// land. Each figure is the mean over its window, not a median over steps. The cases ending in
/// _2threads are the dense ones on two threads (ImpulseParams::threads); those ending in
/// _anchor run with the predicted anchor (ImpulseParams::predictedAnchor), those ending in
/// _corners with edge corners (ImpulseParams::edgeCorners).
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "boxsim/core/world.hpp"
#include "boxsim/impulse_damped/damped_integration.hpp"
#include "boxsim/impulse_damped/impulse_stepper.hpp"
#include "boxsim/io/scene.hpp"
#include "boxsim/io/scene_builders.hpp"

namespace {

using boxsim::DampedIntegrationParams;
using boxsim::DampedIntegrationStepper;
using boxsim::ImpulseStepper;
using boxsim::StepStats;
using boxsim::World;

/// s: the step of every chapter driver and of the command line's default (SimulateOptions).
constexpr double kDt = 1.0 / 60.0;
/// Repetitions of every case: the median of five shrugs off one repetition disturbed by other
/// work on the machine, and keeps the whole run within a few minutes on two cores.
constexpr int kRepetitions = 5;

/// One timed case: a scene, how long to run it before timing, and how many consecutive steps
/// make up the timed window.
struct Case {
  std::string name;   ///< benchmark name after the slash
  std::string scene;  ///< file stem in chapters/impulse_damped/scenes/
  double warmUp = 0;  ///< s simulated outside the timed region
  /// Steps timed in a row from the warm state before both world and stepper are restored.
  /// A scene in motion changes its cost as it evolves; restoring keeps every repetition
  /// timing the same steps, so the repetitions measure noise and not a drifting scene.
  int window = 60;
  /// Windows per repetition: the iteration count is window * windows, fixed rather than
  /// left to --benchmark_min_time, so that the whole run stays within a few minutes on two
  /// cores and every repetition times exactly the same steps.
  int windows = 1;
  /// false: the projectile of a shot scene stays parked at its launch pose during the window,
  /// so the case times the resting pyramid alone, whatever the window's length.
  bool launch = false;
  std::string aim;  ///< the project's target for this case, printed as the label
  /// The world's restitution for the case, or NaN: the scene's own.
  double restitution = std::nan("");
  /// Cubes of a clump built in code (ClumpSpec's defaults, the clump of bench/peers, on its
  /// 150 m ground) instead of the scene file, when > 0.
  int clumpCount = 0;
  /// Coulomb's μ (static and dynamic) on every body, the ground's too, or 0: the scene's own
  /// friction (every scene of these cases is frictionless).
  double friction = 0.0;
};

/// A world and a stepper advanced together to the start of the timed window. Copying both is
/// the reset: the stepper carries state between steps (remembered contact faces, geometric
/// stability flags, sleep counters and resting contacts) that must match the world it steps.
template <class StepperT>
struct WarmState {
  World world;
  StepperT stepper;
  long step = 0;  ///< steps taken so far; the window's next step starts at step * kDt
};

/// The launch time of the step that begins at step k, as simulate() computes it: from k, so
/// time does not drift, and a hair past k dt so a launch at exactly k dt is taken.
double launchClock(long k) { return static_cast<double>(k) * kDt + 1e-9 * kDt; }

/// The case's world at its start.
World sceneOf(const Case& c) {
  if (c.clumpCount <= 0)
    return boxsim::loadScene(std::string(BOXSIM_SCENE_DIR) + "/" + c.scene + ".json").world;
  World world;
  world.addGround(0.0, 150.0, 0.5);
  boxsim::ClumpSpec spec;
  spec.count = c.clumpCount;
  boxsim::addClump(world, spec);
  return world;
}

template <class StepperT>
WarmState<StepperT> warmedUp(const Case& c, const StepperT& fresh) {
  WarmState<StepperT> warm{sceneOf(c), fresh};
  if (!std::isnan(c.restitution)) warm.world.restitution = c.restitution;
  if (c.friction > 0.0)
    for (boxsim::RigidBody& body : warm.world.bodies) body.friction = {c.friction, c.friction};
  const long steps = std::lround(c.warmUp / kDt);
  for (; warm.step < steps; ++warm.step) {
    warm.world.applyLaunches(launchClock(warm.step));
    warm.stepper.step(warm.world, kDt);
  }
  return warm;
}

bool finite(const World& world) {
  for (const boxsim::RigidBody& body : world.bodies)
    if (!body.s.x.allFinite() || !body.s.P.allFinite() || !body.s.L.allFinite()) return false;
  return true;
}

/// A case with its stepper; the warm state is built on the first repetition only (the big
/// clump's warm-up takes seconds) and reused by the others.
template <class StepperT>
struct TimedCase {
  Case c;
  StepperT fresh;
  bool sleeps = false;  ///< report StepStats::sleeping (always 0 for a stepper that never sleeps)
  std::optional<WarmState<StepperT>> warm;

  /// The timed loop: one benchmark iteration is one step.
  void run(benchmark::State& state) {
    if (!warm) warm = warmedUp(c, fresh);
    World world = warm->world;
    StepperT stepper = warm->stepper;
    // Damped integration: where the time goes, stage by stage (DampedStepProfile), and its work.
    boxsim::DampedStepProfile profile;
    const auto watch = [&profile](StepperT& s) {
      if constexpr (std::is_same_v<StepperT, DampedIntegrationStepper>) s.setProfile(&profile);
    };
    watch(stepper);
    int k = 0;
    double contacts = 0.0;
    double sleeping = 0.0;
    bool stillFinite = true;
    for (auto _ : state) {
      if (k == c.window) {
        // The copies allocate (the stepper's contact maps, the world's bodies): untimed.
        state.PauseTiming();
        stillFinite = stillFinite && finite(world);
        world = warm->world;
        stepper = warm->stepper;
        watch(stepper);
        k = 0;
        state.ResumeTiming();
      }
      if (c.launch) world.applyLaunches(launchClock(warm->step + k));
      const StepStats s = stepper.step(world, kDt);
      contacts += s.contacts;
      sleeping += s.sleeping;
      ++k;
    }
    // A timing of a world that blew up is no timing of the scene.
    if (!(stillFinite && finite(world))) {
      state.SkipWithError("a body's state stopped being finite during the timed steps");
      return;
    }
    state.counters["contacts"] = benchmark::Counter(contacts, benchmark::Counter::kAvgIterations);
    if (sleeps)
      state.counters["sleeping"] = benchmark::Counter(sleeping, benchmark::Counter::kAvgIterations);
    if (profile.steps > 0) {
      // ms per step in each stage of A.2 (each with the contact gathering and narrow phases it
      // runs), and separating-axis tests per step, all of them and those of the passes.
      const auto perStep = [&state](const char* name, double total) {
        state.counters[name] = benchmark::Counter(total, benchmark::Counter::kAvgIterations);
      };
      perStep("ms_start", 1e3 * profile.stepContacts);
      perStep("ms_collide", 1e3 * profile.collisionPasses);
      perStep("ms_contact", 1e3 * profile.contactPasses);
      perStep("ms_shock", 1e3 * profile.shockSweep);
      perStep("ms_damp", 1e3 * profile.velocitiesAndDamping);
      perStep("ms_fix", 1e3 * profile.fixContacts);
      perStep("ms_stable", 1e3 * profile.stability);
      perStep("ms_sleep", 1e3 * profile.sleeping);
      perStep("sat", static_cast<double>(profile.narrowPhases));
      perStep("sat_pass", static_cast<double>(profile.passNarrowPhases));
      perStep("sat_start", static_cast<double>(profile.startNarrowPhases));
      perStep("sat_fix", static_cast<double>(profile.fixNarrowPhases));
      perStep("axis_checks", static_cast<double>(profile.axisChecks));
    }
    if (!c.aim.empty()) state.SetLabel(c.aim);
  }
};

DampedIntegrationStepper dampedStepper(bool sleeping, int threads = 1, bool anchor = false,
                                       bool corners = false) {
  DampedIntegrationParams params;
  params.sleep.enabled = sleeping;
  params.impulse.threads = threads;
  params.impulse.predictedAnchor = anchor;
  params.impulse.edgeCorners = corners;
  return DampedIntegrationStepper(params);
}

template <class StepperT>
void registerCase(const std::string& family, const Case& c, const StepperT& stepper,
                  bool sleeps) {
  auto timed = std::make_shared<TimedCase<StepperT>>(TimedCase<StepperT>{c, stepper, sleeps, {}});
  benchmark::RegisterBenchmark((family + "/" + c.name).c_str(),
                               [timed](benchmark::State& state) { timed->run(state); })
      ->Unit(benchmark::kMillisecond)
      ->Iterations(static_cast<benchmark::IterationCount>(c.window) * c.windows)
      ->Repetitions(kRepetitions)
      ->ReportAggregatesOnly(true);
}

void registerAll() {
  // The project's speed targets, for the state each case times.
  const std::string pyramidAim = "target <= 0.35 ms/step (awake)";
  const std::string clumpAim = "target: median <= 4 ms/step";

  // Warm states. The die bounces (restitution 0.9) until about 5.5 s and rests from then on;
  // the tower has settled by 2 s; the pyramids stand settled until the shot at 5 s, and the
  // projectile reaches the base-20 pyramid about 0.65 s after it. The clump's cubes meet in
  // mid-air between 1 and 2.5 s, its costliest phase, and fly apart and land after; at 3 s
  // they are scattered, a middling cost. Resting windows are 1 s of simulated time; the
  // windows of a scene in motion are what fits the time budget.
  // Cheap cases repeat their window more often, so that each repetition is long against the
  // clock's resolution and the pauses around the restores.
  const std::vector<Case> damped = {
      {"die", "die", 7.0, 60, 20, false, ""},
      {"tower10", "tower10", 2.0, 60, 10, false, ""},
      {"pyramid10", "pyramid10_shot", 4.9, 60, 10, false, ""},
      {"pyramid20", "pyramid20_shot", 4.9, 60, 4, false, pyramidAim},
      {"pyramid20_hit", "pyramid20_shot", 5.6, 30, 4, true, ""},
      {"clump100", "clump100", 3.0, 60, 2, false, ""},
      {"clump1000", "clump1000", 3.0, 60, 1, false, clumpAim},
      {"clump1000_collide", "clump1000", 1.5, 30, 1, false, ""},
      // Dense piles at restitution 0 (bench/peers compares them with Bullet and ODE): the
      // settling heap of pile343.json a second after its drop, and the 1000-cube clump piling
      // up on the ground after 2 s.
      {"pile343_settling", "pile343", 1.0, 60, 1, false, ""},
      {"pile343_settling_e09", "pile343", 1.0, 60, 1, false, "", 0.9},
      {"clump1000_e0_pile", "clump1000", 2.0, 60, 1, false, "", 0.0},
      // The same two with Coulomb friction μ = 0.5 (bench/peers' μ rows): friction's share of
      // the step, stage by stage, beside the frictionless cases.
      {"pile343_settling_mu", "pile343", 1.0, 60, 1, false, "", std::nan(""), 0, 0.5},
      {"clump1000_e0_pile_mu", "clump1000", 2.0, 60, 1, false, "", 0.0, 0, 0.5},
  };
  for (const Case& c : damped) {
    Case awake = c;
    awake.name += "_awake";
    registerCase("BM_DampedStep", awake, dampedStepper(false), false);
  }
  for (const Case& c : damped) {
    Case sleeping = c;
    sleeping.name += "_sleeping";
    // The targets are stated for bodies kept awake.
    sleeping.aim.clear();
    registerCase("BM_DampedStep", sleeping, dampedStepper(true), true);
  }
  // The 10 000-cube clump of bench/peers as its lowest layers land and pile up (from 1.5 s),
  // with sleeping on, as the peers run it: a warm-up of about 20 s, so a short window, once.
  const std::vector<Case> large = {
      {"clump10000_e09_landing", "", 1.5, 10, 1, false, "", 0.9, 10000},
      {"clump10000_e0_landing", "", 1.5, 10, 1, false, "", 0.0, 10000},
  };
  for (const Case& c : large) registerCase("BM_DampedStep", c, dampedStepper(true), true);
  // The dense cases on two threads (ImpulseParams::threads): the stages that gain, beside the
  // one-thread cases above; the same steps, bit for bit.
  std::vector<Case> twoThreads = large;
  for (const Case& c : damped)
    if (c.name == "pile343_settling" || c.name == "clump1000_e0_pile" ||
        c.name == "clump1000_e0_pile_mu") {
      twoThreads.push_back(c);
      twoThreads.back().name += "_sleeping";
      twoThreads.back().aim.clear();
    }
  for (Case c : twoThreads) {
    c.name += "_2threads";
    registerCase("BM_DampedStep", c, dampedStepper(true, 2), true);
  }

  // The predicted anchor (ImpulseParams::predictedAnchor, off by default) beside the default
  // on the cases where bodies fast at a step's start are many: the dense piles, the flying
  // clump and the hit pyramid. Its trajectories are its own, so each case times its own steps.
  for (const Case& c : damped)
    if (c.name == "pile343_settling" || c.name == "clump1000_e0_pile" ||
        c.name == "pile343_settling_mu" || c.name == "clump1000_e0_pile_mu" ||
        c.name == "clump1000" || c.name == "pyramid20_hit") {
      Case anchored = c;
      anchored.name += "_sleeping_anchor";
      anchored.aim.clear();
      registerCase("BM_DampedStep", anchored, dampedStepper(true, 1, true), true);
    }
  // Edge corners (ImpulseParams::edgeCorners, off by default) on the piles, where edge-edge
  // pairs rest: what keeping their face corners costs a step.
  for (const Case& c : damped)
    if (c.name == "pile343_settling" || c.name == "clump1000_e0_pile" ||
        c.name == "pile343_settling_mu") {
      Case cornered = c;
      cornered.name += "_sleeping_corners";
      cornered.aim.clear();
      registerCase("BM_DampedStep", cornered, dampedStepper(true, 1, false, true), true);
    }

  // The plain impulse step has no damping (\thesis{§5.3}), so its stacks need not come to
  // rest; these time the scenes in whatever state the step has brought them to.
  const std::vector<Case> impulse = {
      {"die", "die", 7.0, 60, 20, false, ""},
      {"tower10", "tower10", 2.0, 60, 10, false, ""},
      {"pyramid10", "pyramid10_shot", 4.9, 60, 10, false, ""},
  };
  for (const Case& c : impulse) registerCase("BM_ImpulseStep", c, ImpulseStepper(), false);
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  registerAll();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
