// Replays the scene fuzzer's kept inputs (fuzz/corpus/scene_loader/, and every input that once
// revealed a defect, fuzz/regressions/) through the same check the fuzzer makes: each input
// either loads and runs a few steps with finite states, or is rejected with a SceneError (or
// std::invalid_argument) carrying a message. Built with the normal compiler, so it guards the
// fixes in every build; the sanitize preset runs it under ASan and UBSan too.
#include <catch2/catch.hpp>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "../fuzz/scene_fuzz_check.hpp"

namespace fs = std::filesystem;
using boxsim::fuzz::SceneInputOutcome;
using Catch::Matchers::Contains;
using boxsim::fuzz::checkSceneInput;

namespace {

/// The regular files of fuzz/<folder>, sorted by name (README files excepted).
std::vector<fs::path> keptInputs(const std::string& folder) {
  std::vector<fs::path> files;
  for (const fs::directory_entry& e : fs::directory_iterator(fs::path(BOXSIM_SOURCE_DIR) / "fuzz" / folder))
    if (e.is_regular_file() && e.path().filename() != "README.md") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

std::string readBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Checks every input of a folder; returns how many loaded.
int replay(const std::vector<fs::path>& files) {
  int loaded = 0;
  for (const fs::path& file : files) {
    INFO("input: " << file.string());
    SceneInputOutcome outcome;
    CHECK_NOTHROW(outcome = checkSceneInput(readBytes(file)));
    CHECK((outcome.loaded || !outcome.error.empty()));
    loaded += outcome.loaded ? 1 : 0;
  }
  return loaded;
}

}  // namespace

TEST_CASE("Every input of the fuzz corpus loads and runs with finite states or is rejected with a message",
          "[io][fuzz]") {
  const std::vector<fs::path> files = keptInputs("corpus/scene_loader");
  REQUIRE(files.size() >= 7);  // at least the seeds: the shipped scenes and the format example
  const int loaded = replay(files);
  // The seeds are valid scenes, so a loader that rejected everything would fail here.
  CHECK(loaded >= 7);
}

TEST_CASE("Every input that once revealed a loader defect is now loaded or rejected with a message",
          "[io][fuzz]") {
  const std::vector<fs::path> files = keptInputs("regressions");
  REQUIRE(!files.empty());
  replay(files);
}

TEST_CASE("Numbers that would underflow or overflow the physics are rejected with the place, the range and the fix",
          "[io][fuzz]") {
  // Each input was accepted once and gave a state that was not finite after one step.
  const auto errorOf = [](const std::string& file) {
    return checkSceneInput(readBytes(fs::path(BOXSIM_SOURCE_DIR) / "fuzz/regressions" / file)).error;
  };
  const std::string tiny = errorOf("tiny_half_extents_nan_state.json");
  CHECK_THAT(tiny, Contains("/bodies/0/half_extents/0: must lie in [1e-06, 1e+06] m (got 1e-200)"));
  CHECK_THAT(tiny, Contains("Fix:"));
  CHECK_THAT(errorOf("tiny_tower_size_nan_state.json"),
             Contains("/builders/0/size: must lie in [1e-06, 1e+06] m (got 1e-300)"));
  CHECK_THAT(errorOf("huge_inertia_times_spin_overflow.json"),
             Contains("/bodies/0/half_extents/0: must lie in [1e-06, 1e+06] m (got 1e+300)"));
}

TEST_CASE("A clump whose size reaches the default spacing names the size key", "[io][fuzz]") {
  // Once escaped the loader as nlohmann::json::out_of_range: the error named "spacing", a key
  // the builder did not have.
  const std::string e =
      checkSceneInput(readBytes(fs::path(BOXSIM_SOURCE_DIR) /
                                "fuzz/regressions/clump_size_without_spacing_uncaught_json_error.json"))
          .error;
  CHECK_THAT(e, Contains("/builders/0/size: the spacing (2 m unless given) must exceed the cube size"));
}

TEST_CASE("Scenes at the edges of the allowed ranges load and run with finite states", "[io][fuzz]") {
  // The smallest and largest sizes and masses, at the largest speeds, spins and gravity: the
  // ranges are the ones the physics carries, not merely ones that reject the findings.
  const std::string tinyFast = R"({"ground": {}, "bodies": [{"half_extents": [1e-6, 1e-6, 1e-6],
      "mass": 1e6, "position": [0, 1e-6, 0], "angular_velocity": [1e6, 1e6, 0],
      "velocity": [0, -1e6, 0]}]})";
  const std::string flatHeavy = R"({"gravity": [1e6, -1e6, 1e6],
      "ground": {"half_size": 1e6, "half_thickness": 1e6},
      "bodies": [{"half_extents": [1e6, 1e-6, 1e6], "mass": 1e6, "position": [0, 1e-6, 0],
                  "angular_velocity": [1e6, -1e6, 1e6], "velocity": [1e6, -1e6, 0]}]})";
  const std::string hugeOnTiny = R"({"ground": {}, "bodies": [
      {"half_extents": [1e-6, 1e-6, 1e-6], "mass": 1e-6, "position": [0, 1e-6, 0]},
      {"half_extents": [1e6, 4e5, 1e6], "mass": 1e6, "position": [0, 400000.000002, 0],
       "velocity": [0, -1e6, 0]}]})";
  for (const std::string& text : {tinyFast, flatHeavy, hugeOnTiny}) {
    INFO(text);
    SceneInputOutcome outcome;
    REQUIRE_NOTHROW(outcome = checkSceneInput(text));
    INFO("loader: " << outcome.error);
    CHECK(outcome.loaded);
    CHECK(outcome.simulated);
  }
}

TEST_CASE("Basic colliding ends a step whose launched body starts inside the ground instead of hanging",
          "[basic_colliding][fuzz]") {
  // The loader now rejects such a scene (regression launch_inside_immovable_hang.json); a world
  // built in code can still hold one. Before the fix the step's hold loop never ended.
  boxsim::World world;
  world.addGround(0.0, 50.0, 0.5);
  boxsim::RigidBody box = boxsim::RigidBody::box(boxsim::Vec3(0.5, 0.5, 0.5), 1.0);
  box.s.x = boxsim::Vec3(0.0, 0.2, 0.0);  // 0.3 m into the ground
  box.updateDerived();
  world.addLaunched(box, "projectile", 0.0);
  world.applyLaunches(0.0);
  const std::unique_ptr<boxsim::Stepper> stepper = boxsim::makeStepper("basic_colliding");
  const boxsim::StepStats stats = stepper->step(world, 1.0 / 60.0);
  CHECK(stats.limitReached);
  CHECK(world.bodies[1].s.x.allFinite());
}
