/// \file
/// What the scene fuzzer does with one input, shared by the libFuzzer target
/// (scene_loader_fuzz.cpp) and the regression test that replays the kept inputs
/// (verification/scene_fuzz_regression_test.cpp), so that both check the same thing.
///
/// An input is text handed to parseScene(), the entry `boxsim run` uses (through loadScene()).
/// Bad input must end in a SceneError (or std::invalid_argument) with a non-empty message. A
/// scene that loads is then run for a few steps, so that numbers the validator lets through but
/// the physics cannot take (a NaN in the state) are found too.
#pragma once

#include <algorithm>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "boxsim/io/recorder.hpp"
#include "boxsim/io/scene.hpp"
#include "boxsim/io/simulate.hpp"
#include "boxsim/techniques.hpp"

namespace boxsim::fuzz {

/// Largest scene (bodies, the ground included) that is stepped by damped integration; larger
/// scenes are only loaded, so that one input costs milliseconds, not seconds.
inline constexpr std::size_t kMaxSimulatedBodies = 64;
/// Largest scene also stepped by the basic colliding method. Its cost on bodies at rest grows
/// with events × bodies up to its events-per-step limit (\thesis{§4.3}): a tower of 10 takes
/// about 0.5 s a step under the sanitizers, too slow for a fuzzer.
inline constexpr std::size_t kMaxBasicCollidingBodies = 4;
/// Steps of each technique run on a scene that loads.
inline constexpr int kSimulatedSteps = 5;
/// Time step of those runs, s: the command line's default.
inline constexpr double kDt = 1.0 / 60.0;

/// The outcome of one input that did not reveal a defect.
struct SceneInputOutcome {
  bool loaded = false;  ///< true: the scene loaded (and ran, when small enough)
  bool simulated = false;  ///< true: it was also stepped (small enough for damped integration)
  std::string error;    ///< the loader's message when it was rejected (never empty then)
};

/// Runs `method` on a copy of the scene's world for kSimulatedSteps steps of kDt through
/// simulate(), which throws std::runtime_error naming the step and the body as soon as a state
/// stops being finite.
inline void runBriefly(const Scene& scene, const std::string& method) {
  World world = scene.world;
  const std::unique_ptr<Stepper> stepper = makeStepper(method);
  Recorder recorder(world, runParameters(*stepper, world, scene.source, kDt, kSimulatedSteps * kDt));
  SimulateOptions options;
  options.dt = kDt;
  options.duration = kSimulatedSteps * kDt;
  simulate(world, *stepper, options, recorder);
}

/// Feeds `text` to parseScene() and, when it loads, runs it briefly: under damped integration
/// (\thesis{§5.2}, the command line's default method) when it has at most kMaxSimulatedBodies
/// bodies, and under basic colliding (\thesis{§2.1}, the naive baseline) when it has at most
/// kMaxBasicCollidingBodies. Returns the outcome when the input was handled as documented: loaded (and
/// ran), or rejected with a SceneError or std::invalid_argument carrying a message.
/// Throws std::logic_error for a rejection with an empty message; lets any other exception
/// escape (from the loader, or a std::runtime_error from a run whose state stopped being
/// finite): both are defects.
inline SceneInputOutcome checkSceneInput(const std::string& text) {
  SceneInputOutcome outcome;
  std::optional<Scene> scene;
  try {
    scene = parseScene(text, "fuzz.json");
  } catch (const SceneError& e) {
    outcome.error = e.what();
  } catch (const std::invalid_argument& e) {
    outcome.error = e.what();
  }
  if (!scene) {
    if (outcome.error.empty()) throw std::logic_error("the scene was rejected with an empty message");
    return outcome;
  }
  outcome.loaded = true;
  const std::size_t bodies = scene->world.bodies.size();
  if (bodies <= kMaxBasicCollidingBodies) runBriefly(*scene, "basic_colliding");
  if (bodies <= kMaxSimulatedBodies) {
    runBriefly(*scene, "damped");
    outcome.simulated = true;
  }
  return outcome;
}

}  // namespace boxsim::fuzz
