// End-to-end checks of the `boxsim` command: a good run writes a trajectory, every bad input
// exits non-zero with an error naming the file and the place, and leaves no output file.
#include <stdlib.h>
#include <sys/wait.h>

#include <catch2/catch.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "boxsim/io/trajectory.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

struct Result {
  int status;
  std::string stderrText;
};

/// A fresh folder of the test's own (CTest runs the cases in parallel), removed at the end.
class ScratchDir {
 public:
  ScratchDir() {
    std::string pattern = (fs::temp_directory_path() / "boxsim_cli_test_XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
    path_ = pattern;
  }
  ~ScratchDir() { fs::remove_all(path_); }
  fs::path operator/(const std::string& name) const { return path_ / name; }

 private:
  fs::path path_;
};

Result runBoxsim(const ScratchDir& kDir, const std::string& arguments) {
  const fs::path errPath = kDir / "stderr.txt";
  const std::string command = std::string(BOXSIM_BINARY_DIR) + "/boxsim " + arguments + " 2> " +
                              errPath.string() + " > /dev/null";
  const int raw = std::system(command.c_str());
  std::ifstream in(errPath);
  std::stringstream text;
  text << in.rdbuf();
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, text.str()};
}

std::string writeScene(const ScratchDir& kDir, const std::string& name, const std::string& text) {
  const fs::path p = kDir / name;
  std::ofstream(p) << text;
  return p.string();
}

/// The bytes of a file ("" when it cannot be read).
std::string contentsOf(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

}  // namespace

TEST_CASE("boxsim run writes the trajectory of the die scene", "[cli]") {
  const ScratchDir kDir;
  const std::string out = (kDir / "die.dat").string();
  const Result r = runBoxsim(kDir, "run " + std::string(BOXSIM_SOURCE_DIR) +
                             "/chapters/basic_colliding/scenes/die.json --method basic_colliding "
                             "--dt 0.0166666 --duration 1 --out " + out);
  CHECK(r.status == 0);
  const boxsim::Trajectory t = boxsim::readTrajectory(out);
  CHECK(t.frames.size() == 61);
  CHECK(t.meta.at("method") == "basic_colliding");
  CHECK(t.meta.at("integrator") == "semi_implicit_euler");
  CHECK(t.meta.count("seed") == 1);
}

TEST_CASE("Every bad scene exits non-zero with its error and writes nothing", "[cli][input]") {
  const ScratchDir kDir;
  const std::string body = R"({"half_extents": [0.5,0.5,0.5], "mass": 1, "position": [0,3,0]})";
  struct Case {
    const char* file;
    std::string text;
    const char* expected;
  };
  const Case cases[] = {
      {"malformed.json", "{\n \"bodies\": [\n", "malformed.json:3:"},
      {"unknown_key.json", R"({"bodies": [{"half_extents": [1,1,1], "mass": 1, "colour": "red"}]})",
       "/bodies/0/colour: unknown key"},
      {"non_finite.json", R"({"bodies": [{"half_extents": [1,1,1], "mass": 1, "position": [0, 1e400, 0]}]})",
       "non_finite.json"},
      {"negative_mass.json", R"({"bodies": [{"half_extents": [1,1,1], "mass": -1}]})",
       "/bodies/0/mass: must be > 0 kg"},
      {"zero_extent.json", R"({"bodies": [{"half_extents": [1,0,1], "mass": 1}]})",
       "/bodies/0/half_extents/1: must be > 0 m"},
      {"overlap.json", "{\"bodies\": [" + body + "," + body + "]}", "overlap"},
  };
  for (const Case& c : cases) {
    const std::string scene = writeScene(kDir, c.file, c.text);
    const std::string out = (kDir / (std::string(c.file) + ".dat")).string();
    const Result r = runBoxsim(kDir, "run " + scene + " --duration 0.1 --out " + out);
    INFO(c.file << ": " << r.stderrText);
    CHECK(r.status != 0);
    CHECK_THAT(r.stderrText, Contains(c.expected));
    CHECK_THAT(r.stderrText, Contains(c.file));
    CHECK_FALSE(fs::exists(out));
  }
}

TEST_CASE("An unknown method or a bad time step exits non-zero and writes nothing", "[cli][input]") {
  const ScratchDir kDir;
  const std::string scene = std::string(BOXSIM_SOURCE_DIR) + "/chapters/basic_colliding/scenes/die.json";
  const std::string out = (kDir / "x.dat").string();
  const Result method = runBoxsim(kDir, "run " + scene + " --method teleport --out " + out);
  CHECK(method.status != 0);
  CHECK_THAT(method.stderrText, Contains("unknown method 'teleport'"));
  CHECK_THAT(method.stderrText, Contains("basic_colliding"));
  const Result dt = runBoxsim(kDir, "run " + scene + " --dt -1 --out " + out);
  CHECK(dt.status != 0);
  CHECK_THAT(dt.stderrText, Contains("--dt"));
  CHECK_FALSE(fs::exists(out));
  const Result nanStep = runBoxsim(kDir, "run " + scene + " --dt nan --out " + out);
  CHECK(nanStep.status != 0);
  CHECK_THAT(nanStep.stderrText, Contains("time step"));
  const Result huge = runBoxsim(kDir, "run " + scene + " --duration 1e300 --out " + out);
  CHECK(huge.status != 0);
  CHECK_THAT(huge.stderrText, Contains("steps"));
  CHECK_FALSE(fs::exists(out));
  const Result missing = runBoxsim(kDir, "run " + (kDir / "nope.json").string() + " --out " + out);
  CHECK(missing.status != 0);
  CHECK_THAT(missing.stderrText, Contains("nope.json"));
}

TEST_CASE("boxsim run --broad-phase all_pairs writes the default run's file byte for byte, and an "
          "unknown name exits non-zero and writes nothing",
          "[cli][input]") {
  const ScratchDir kDir;
  // The thesis' pyramid (Fig. 6.6): 145 pairs touching every step.
  const std::string scene =
      std::string(BOXSIM_SOURCE_DIR) + "/chapters/impulse_damped/scenes/pyramid10_shot.json";
  const std::string swept = (kDir / "swept.dat").string();
  const std::string all = (kDir / "all.dat").string();
  REQUIRE(runBoxsim(kDir, "run " + scene + " --method damped --duration 1 -q --out " + swept)
              .status == 0);
  REQUIRE(runBoxsim(kDir, "run " + scene +
                              " --method damped --duration 1 -q --broad-phase all_pairs --out " +
                              all)
              .status == 0);
  const std::string sweptText = contentsOf(swept);
  CHECK(!sweptText.empty());
  CHECK(sweptText == contentsOf(all));

  const std::string bad = (kDir / "bad.dat").string();
  const Result r = runBoxsim(kDir, "run " + scene + " --broad-phase octree --out " + bad);
  CHECK(r.status != 0);
  CHECK_THAT(r.stderrText, Contains("--broad-phase"));
  CHECK_THAT(r.stderrText, Contains("octree"));
  CHECK_FALSE(fs::exists(bad));
}

TEST_CASE("Technique options reach the stepper and its header, and options a method lacks "
          "are refused",
          "[cli][input]") {
  const ScratchDir kDir;
  const std::string die = std::string(BOXSIM_SOURCE_DIR) + "/chapters/impulse_damped/scenes/die.json";
  const std::string out = (kDir / "damped.dat").string();
  const Result r = runBoxsim(kDir, "run " + die + " --method damped --duration 0.5 --sleep off "
                                   "--contact-normal signed_distance --plausibility-seed 42 --out " + out);
  REQUIRE(r.status == 0);
  const boxsim::Trajectory t = boxsim::readTrajectory(out);
  CHECK(t.meta.at("seed") == "42");
  CHECK(t.meta.at("plausibility") == "on");
  CHECK(t.meta.at("sleep") == "off");
  CHECK(t.meta.at("contact_normal") == "signed_distance");
  const std::string refused = (kDir / "refused.dat").string();
  const Result basic = runBoxsim(kDir, "run " + die + " --method basic_colliding --sleep off --out " + refused);
  CHECK(basic.status != 0);
  CHECK_THAT(basic.stderrText, Contains("takes no sleep option"));
  const Result impulse = runBoxsim(kDir, "run " + die + " --method impulse --integrator forward_euler --out " + refused);
  CHECK(impulse.status != 0);
  CHECK_THAT(impulse.stderrText, Contains("semi_implicit_euler or split_rotation"));
  const Result unknown = runBoxsim(kDir, "run " + die + " --method damped --integrator leapfrog --out " + refused);
  CHECK(unknown.status != 0);
  CHECK_THAT(unknown.stderrText, Contains("unknown integrator 'leapfrog'"));
  CHECK_FALSE(fs::exists(refused));
  const Result split = runBoxsim(kDir, "run " + die + " --method damped --duration 0.1 --integrator split_rotation --out " + out);
  REQUIRE(split.status == 0);
  CHECK(boxsim::readTrajectory(out).meta.at("integrator") == "split_rotation");
  const Result ccd = runBoxsim(kDir, "run " + die + " --method damped --duration 0.1 --continuous-collision on --out " + out);
  REQUIRE(ccd.status == 0);
  CHECK(boxsim::readTrajectory(out).meta.at("continuous_collision") == "on");
  const Result noCcd = runBoxsim(kDir, "run " + die + " --method impulse --continuous-collision on --out " + refused);
  CHECK(noCcd.status != 0);
  CHECK_THAT(noCcd.stderrText, Contains("takes no continuous collision option"));
}

TEST_CASE("boxsim render --colour colours a named body, and a bad name or colour exits non-zero",
          "[cli][input][render]") {
  const ScratchDir kDir;
  const std::string traj = (kDir / "die.dat").string();
  REQUIRE(runBoxsim(kDir, "run " + std::string(BOXSIM_SOURCE_DIR) +
                              "/chapters/basic_colliding/scenes/die.json --duration 0.1 --out " +
                              traj)
              .status == 0);
  const std::string png = (kDir / "die.png").string();
  CHECK(runBoxsim(kDir, "render " + traj + " --out " + png + " --colour die=#666666").status == 0);
  CHECK(fs::file_size(png) > 0);
  const std::string bad = (kDir / "bad.png").string();
  const Result name = runBoxsim(kDir, "render " + traj + " --out " + bad + " --colour dye=666666");
  CHECK(name.status != 0);
  CHECK_THAT(name.stderrText, Contains("'dye'"));
  const Result colour = runBoxsim(kDir, "render " + traj + " --out " + bad + " --colour die=66666g");
  CHECK(colour.status != 0);
  CHECK_THAT(colour.stderrText, Contains("NAME=RRGGBB"));
  CHECK_FALSE(fs::exists(bad));
}

TEST_CASE("boxsim run --filter writes the filtered trajectory and names the filter in its header",
          "[cli][filtering]") {
  const ScratchDir kDir;
  const std::string die = std::string(BOXSIM_SOURCE_DIR) + "/chapters/impulse_damped/scenes/die.json";
  const std::string raw = (kDir / "raw.dat").string();
  const std::string box = (kDir / "box.dat").string();
  REQUIRE(runBoxsim(kDir, "run " + die + " --method impulse --duration 1 -q --out " + raw).status == 0);
  REQUIRE(runBoxsim(kDir, "run " + die + " --method impulse --duration 1 -q --filter box "
                          "--filter-half-width 3 --out " + box).status == 0);
  const boxsim::Trajectory r = boxsim::readTrajectory(raw);
  const boxsim::Trajectory b = boxsim::readTrajectory(box);
  REQUIRE(b.frames.size() == r.frames.size());
  CHECK(b.meta.at("filter") == "box");
  CHECK(b.meta.at("box_half_width") == "3");
  CHECK(b.frames.back().t == r.frames.back().t);
  // In free fall (the die lands at frame 32) the filter lowers the parabola by g dt^2 H(H+1)/6.
  CHECK(b.frames[20].x[1].y() < r.frames[20].x[1].y());
  const std::string envelope = (kDir / "envelope.dat").string();
  REQUIRE(runBoxsim(kDir, "run " + die + " --method impulse --duration 1 -q --filter envelope "
                          "--envelope-radius 0.05 --envelope-angle 0.1 --out " + envelope).status == 0);
  const boxsim::Trajectory e = boxsim::readTrajectory(envelope);
  CHECK(e.meta.at("filter") == "envelope");
  CHECK(e.meta.at("envelope_radius") == "0.05 m");
  CHECK(e.meta.at("envelope_angle") == "0.1 rad");
}

TEST_CASE("boxsim filter filters a recorded run, and bad filter options exit non-zero and "
          "write nothing",
          "[cli][filtering][input]") {
  const ScratchDir kDir;
  const std::string die = std::string(BOXSIM_SOURCE_DIR) + "/chapters/impulse_damped/scenes/die.json";
  const std::string raw = (kDir / "raw.dat").string();
  REQUIRE(runBoxsim(kDir, "run " + die + " --method impulse --duration 1 -q --out " + raw).status == 0);
  const std::string out = (kDir / "env.dat").string();
  REQUIRE(runBoxsim(kDir, "filter " + raw + " --filter envelope -o " + out).status == 0);
  const boxsim::Trajectory e = boxsim::readTrajectory(out);
  CHECK(e.frames.size() == boxsim::readTrajectory(raw).frames.size());
  CHECK(e.meta.at("filter") == "envelope");
  CHECK(e.meta.at("method") == "impulse");  // the run's own header lines are kept

  const std::string bad = (kDir / "bad.dat").string();
  struct Case {
    std::string arguments;
    const char* expected;
  };
  const Case cases[] = {
      {"filter " + raw + " --filter box --filter-half-width -1 -o " + bad, "half width"},
      {"filter " + raw + " --filter envelope --envelope-radius -0.1 -o " + bad, "--envelope-radius"},
      {"filter " + raw + " --filter envelope --envelope-angle nan -o " + bad, "--envelope-angle"},
      {"filter " + raw + " --filter box --envelope-radius 0.1 -o " + bad, "takes no --envelope-radius"},
      {"filter " + raw + " --filter envelope --filter-half-width 2 -o " + bad, "takes no --filter-half-width"},
      {"filter " + raw + " --filter blur -o " + bad, "blur"},
      {"filter " + raw + " -o " + bad, "--filter"},
      {"run " + die + " --filter-half-width 2 -o " + bad, "need a filter"},
      {"run " + die + " --filter envelope --envelope-radius inf -o " + bad, "--envelope-radius"},
  };
  for (const Case& c : cases) {
    INFO(c.arguments);
    const Result r = runBoxsim(kDir, c.arguments);
    CHECK(r.status != 0);
    CHECK_THAT(r.stderrText, Contains(c.expected));
    CHECK_FALSE(fs::exists(bad));
  }
}
