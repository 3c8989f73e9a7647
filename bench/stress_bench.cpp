/// \file
/// The long randomized stress run: every technique of `boxsim run --method` on many random
/// scenes (verification/random_scenes.hpp: sizes 0.05-5 m, masses up to 1000:1, speeds up to
/// 50 m/s, piles, boxes at rest, Δt from 1e-4 s to 1/10 s), each step checked for finite
/// states, bodies sinking through the ground and, for damped integration, energy rising
/// (runStressChecks states every tolerance and where it comes from). verification/stress_test.cpp runs a few of the same scenes in every test run;
/// this runs thousands and prints the number of scenes and steps covered and every failure with
/// the seed that rebuilds it. Exit status 1 when anything failed.
///
///     boxsim_stress_bench --scenes 2000 --first-seed 1 --method damped
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "boxsim/techniques.hpp"
#include "random_scenes.hpp"

namespace {

using namespace boxsim;
using namespace boxsim::testing;

struct Totals {
  long scenes = 0;
  long steps = 0;
  long limitedSteps = 0;
  long failures = 0;
  double deepest = 0.0;  // m
  double seconds = 0.0;
};

/// Prints the scene, then after every step the mechanical energy against the start and, per
/// movable body, its lowest vertex, centre, velocity, spin and energy.
void trace(const RandomScene& scene, const std::string& method) {
  World world = scene.world;
  const std::unique_ptr<Stepper> stepper = makeStepper(method);
  std::printf("%s %s\n", method.c_str(), scene.describe().c_str());
  const auto print = [&](int k, const StepStats& stats) {
    std::printf("step %d: E - E0 = %.9g J, events %d, contacts %d%s\n", k,
                mechanicalEnergy(world) - mechanicalEnergy(scene.world), stats.events,
                stats.contacts, stats.limitReached ? ", limit reached" : "");
    for (std::size_t i = 0; i < world.bodies.size(); ++i) {
      const RigidBody& b = world.bodies[i];
      if (b.immovable) continue;
      double lowest = b.s.x.y();
      for (int a = 0; a < 3; ++a) lowest -= b.halfExtents[a] * std::abs(b.R(1, a));
      std::printf("  %zu: h (%.4g %.4g %.4g) m %.4g kg, lowest %.6g, x (%.6g %.6g %.6g), "
                  "v (%.4g %.4g %.4g), w (%.4g %.4g %.4g), KE %.6g, PE %.9g\n",
                  i, b.halfExtents.x(), b.halfExtents.y(), b.halfExtents.z(), b.mass, lowest,
                  b.s.x.x(), b.s.x.y(), b.s.x.z(), b.v.x(), b.v.y(), b.v.z(), b.omega.x(),
                  b.omega.y(), b.omega.z(), b.kineticEnergy(),
                  -b.mass * world.gravity.dot(b.s.x));
    }
  };
  print(0, StepStats{});
  for (int k = 1; k <= scene.steps; ++k) print(k, stepper->step(world, scene.dt));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("Randomized stress run of every boxsim technique");
  long scenes = 1000;
  unsigned long firstSeed = 1;
  std::vector<std::string> methods;
  int steps = 0;
  bool verbose = false;
  long traceSeed = -1;
  app.add_option("--scenes,-n", scenes, "Scenes per technique")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--first-seed", firstSeed, "Seed of the first scene; the others follow")->capture_default_str();
  app.add_option("--method,-m", methods, "Techniques to run (default: all of boxsim run --method)");
  app.add_option("--steps", steps, "Most steps per scene (default: the technique's, affordableSpec)")
      ->check(CLI::PositiveNumber);
  app.add_flag("--verbose,-v", verbose, "One line per scene");
  app.add_option("--trace", traceSeed,
                 "Rebuild the scene of this seed and print every body after every step");
  CLI11_PARSE(app, argc, argv);
  if (methods.empty()) methods = methodNames();
  if (traceSeed >= 0) {
    for (const std::string& method : methods) {
      RandomSceneSpec spec = affordableSpec(method);
      if (steps > 0) spec.steps = steps;
      trace(randomScene(static_cast<unsigned long>(traceSeed), spec), method);
    }
    return 0;
  }

  long allScenes = 0, allSteps = 0, allFailures = 0;
  for (const std::string& method : methods) {
    RandomSceneSpec spec = affordableSpec(method);
    if (steps > 0) spec.steps = steps;
    Totals totals;
    const auto start = std::chrono::steady_clock::now();
    for (long n = 0; n < scenes; ++n) {
      const unsigned long seed = firstSeed + static_cast<unsigned long>(n);
      const RandomScene scene = randomScene(seed, spec);
      const std::unique_ptr<Stepper> stepper = makeStepper(method);
      const StressOutcome outcome = runStressChecks(scene, *stepper);
      ++totals.scenes;
      totals.steps += outcome.steps;
      totals.limitedSteps += outcome.limitedSteps;
      totals.deepest = std::max(totals.deepest, outcome.deepestBelowGround);
      if (verbose)
        std::printf("%s %s: %ld steps, deepest %.3g m, energy rise %.3g J (orientation bound %.3g J)\n",
                    method.c_str(), scene.describe().c_str(), outcome.steps,
                    outcome.deepestBelowGround, outcome.largestEnergyRise, outcome.rotationGain);
      if (!outcome.failure.empty()) {
        ++totals.failures;
        std::printf("FAIL %s %s: %s\n", method.c_str(), scene.describe().c_str(),
                    outcome.failure.c_str());
      }
      std::fflush(stdout);
    }
    totals.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("%-16s %6ld scenes %9ld steps %6ld limited %4ld failed, deepest %.3g m, %.1f s\n",
                method.c_str(), totals.scenes, totals.steps, totals.limitedSteps, totals.failures,
                totals.deepest, totals.seconds);
    std::fflush(stdout);
    allScenes += totals.scenes;
    allSteps += totals.steps;
    allFailures += totals.failures;
  }
  std::printf("all: %ld scene runs, %ld steps, %ld failed\n", allScenes, allSteps, allFailures);
  return allFailures > 0 ? 1 : 0;
}
