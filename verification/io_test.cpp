// Verification of scene loading (every kind of bad input gets an error that names the file,
// the place and the fix), the named builders, trajectory files and atomic output.
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "boxsim/io/atomic_file.hpp"
#include "boxsim/core/frame_sink.hpp"
#include "boxsim/io/scene.hpp"
#include "boxsim/io/scene_builders.hpp"
#include "boxsim/io/trajectory.hpp"
#include "boxsim/io/trajectory_file_writer.hpp"
#include "boxsim/techniques.hpp"

using namespace boxsim;
using Catch::Matchers::Contains;

namespace {
std::string errorOf(const std::string& text) {
  try {
    parseScene(text, "bad.json");
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no error)";
}
const std::string kBody = R"({"half_extents": [0.5, 0.5, 0.5], "mass": 1, "position": [0, 3, 0]})";
}  // namespace

TEST_CASE("Malformed JSON is reported with file, line and column", "[io][input]") {
  const std::string e = errorOf("{\n  \"bodies\": [\n    {\"mass\": 1,,}\n  ]\n}");
  CHECK_THAT(e, Contains("bad.json:3:"));
  CHECK_THAT(e, Contains("malformed JSON"));
  CHECK_THAT(e, Contains("Fix:"));
}

TEST_CASE("Unknown keys are reported with their JSON path and the known keys", "[io][input]") {
  const std::string e = errorOf(R"({"bodies": [{"half_extents": [1,1,1], "masss": 1}]})");
  CHECK_THAT(e, Contains("bad.json: /bodies/0/masss: unknown key"));
  CHECK_THAT(e, Contains("mass"));
  CHECK_THAT(errorOf(R"({"gravty": [0, -9.81, 0]})"), Contains("/gravty: unknown key"));
}

TEST_CASE("Non-finite numbers are rejected", "[io][input]") {
  // JSON has no NaN or infinity literal; an overflowing literal is the way one gets in.
  const std::string e = errorOf(R"({"bodies": [{"half_extents": [0.5,0.5,0.5], "mass": 1e999}]})");
  CHECK_THAT(e, Contains("bad.json:1:53: the number 1e999 is not finite"));
  // The literals C and JavaScript print are malformed JSON, and the error says why.
  for (const std::string word : {"NaN", "Infinity", "-Infinity"}) {
    INFO(word);
    const std::string literal =
        errorOf(R"({"bodies": [{"half_extents": [0.5,0.5,0.5], "mass": )" + word + "}]}");
    CHECK_THAT(literal, Contains("bad.json:1:"));
    CHECK_THAT(literal, Contains("is not a number in JSON"));
    CHECK_THAT(literal, Contains("Fix: write a finite number"));
  }
}

TEST_CASE("Non-positive masses and extents are rejected with the value and the fix", "[io][input]") {
  const std::string mass = errorOf(R"({"bodies": [{"half_extents": [0.5,0.5,0.5], "mass": -2}]})");
  CHECK_THAT(mass, Contains("/bodies/0/mass: must be > 0 kg (got -2)"));
  CHECK_THAT(mass, Contains("Fix:"));
  const std::string extent = errorOf(R"({"bodies": [{"half_extents": [0.5,0,0.5], "mass": 1}]})");
  CHECK_THAT(extent, Contains("/bodies/0/half_extents/1: must be > 0 m"));
  CHECK_THAT(errorOf(R"({"builders": [{"type": "tower", "count": 0}]})"), Contains("/builders/0/count"));
  CHECK_THAT(errorOf(R"({"builders": [{"type": "tower", "size": -1}]})"), Contains("/builders/0/size"));
}

TEST_CASE("Wrong types, unknown builders and empty scenes are rejected", "[io][input]") {
  CHECK_THAT(errorOf(R"({"bodies": [{"half_extents": "big", "mass": 1}]})"),
             Contains("/bodies/0/half_extents: expected an array of 3 numbers"));
  CHECK_THAT(errorOf(R"({"builders": [{"type": "castle"}]})"),
             Contains("/builders/0/type: unknown builder type \"castle\""));
  CHECK_THAT(errorOf(R"({"ground": {}})"), Contains("no movable body"));
  CHECK_THAT(errorOf(R"([1, 2])"), Contains("expected a scene"));
  CHECK_THAT(errorOf("{\"bodies\": [" + kBody + ", " + kBody + "]}"), Contains("overlap"));
  CHECK_THAT(errorOf(R"({"builders": [{"type": "pyramid", "base": 1000000}]})"),
             Contains("/builders/0/base: the scene would hold"));
}

TEST_CASE("The key broad_phase chooses the world's broad phase, and an unknown name is rejected "
          "with the valid ones",
          "[io][input]") {
  CHECK(parseScene("{\"bodies\": [" + kBody + "]}", "s.json").world.broadPhase ==
        BroadPhase::SweepAndPrune);
  CHECK(parseScene("{\"broad_phase\": \"all_pairs\", \"bodies\": [" + kBody + "]}", "s.json")
            .world.broadPhase == BroadPhase::AllPairs);
  CHECK(parseScene("{\"broad_phase\": \"sweep_and_prune\", \"bodies\": [" + kBody + "]}",
                   "s.json")
            .world.broadPhase == BroadPhase::SweepAndPrune);
  const std::string e = errorOf("{\"broad_phase\": \"octree\", \"bodies\": [" + kBody + "]}");
  CHECK_THAT(e, Contains("bad.json: /broad_phase: unknown broad phase \"octree\""));
  CHECK_THAT(e, Contains("all_pairs") && Contains("sweep_and_prune"));
  CHECK_THAT(errorOf("{\"broad_phase\": 1, \"bodies\": [" + kBody + "]}"),
             Contains("/broad_phase: expected a string"));
}

TEST_CASE("Body names must be unique, the ground's included", "[io][input]") {
  CHECK_THAT(errorOf(R"({"ground": {}, "bodies": [
      {"name": "ground", "half_extents": [0.5,0.5,0.5], "mass": 1, "position": [0, 3, 0]}]})"),
             Contains("/bodies/0/name: the name \"ground\" is already taken"));
  // An unnamed body's default name colliding with an explicit one is reported on the body.
  CHECK_THAT(errorOf(R"({"bodies": [
      {"name": "body_1", "half_extents": [0.5,0.5,0.5], "mass": 1, "position": [0, 3, 0]},
      {"half_extents": [0.5,0.5,0.5], "mass": 1, "position": [5, 3, 0]}]})"),
             Contains("/bodies/1: the name \"body_1\" is already taken"));
}

TEST_CASE("Boxes overlapping at the start are named, and touching boxes are accepted",
          "[io][input]") {
  const std::string e = errorOf(R"({"ground": {}, "bodies": [
      {"name": "a", "half_extents": [0.5,0.5,0.5], "mass": 1, "position": [0, 0.4, 0]}]})");
  CHECK_THAT(e, Contains("/ground and /bodies/0"));
  CHECK_THAT(e, Contains("overlap by 0.1"));
  // A tower stands with its boxes exactly touching.
  const Scene tower = parseScene(R"({"ground": {}, "builders": [{"type": "tower", "count": 5}]})", "t.json");
  CHECK(tower.world.bodies.size() == 6);
}

TEST_CASE("An unknown method is rejected with the list of known methods", "[io][input]") {
  CHECK_THROWS_WITH(makeStepper("magic"), Contains("unknown method 'magic'") && Contains("basic_colliding"));
}

TEST_CASE("The shipped die scene loads as the thesis describes", "[io][scene]") {
  const Scene s = loadScene(std::string(BOXSIM_SOURCE_DIR) + "/chapters/basic_colliding/scenes/die.json");
  REQUIRE(s.world.bodies.size() == 2);
  CHECK(s.world.groundIndex == 0);
  CHECK(s.world.restitution == 0.9);
  const RigidBody& die = s.world.bodies[1];
  // Tilted by 10 degrees: the angle between its y axis and the world's.
  CHECK(std::acos(die.R.col(1).dot(Vec3::UnitY())) * 180.0 / 3.14159265358979 == Approx(10.0));
  CHECK(die.mass == 1.0);
}

TEST_CASE("The builders make the thesis' scenes", "[io][scene]") {
  World w;
  CHECK(addPyramid(w, PyramidSpec{10}) == 55);
  CHECK(w.bodies.back().s.x.y() == Approx(9.5));  // apex: tenth row
  // Fig. 5.6: the bottom centre of a base of 9 left out, by (row, index in the row).
  World holed;
  CHECK(addPyramid(holed, PyramidSpec{9}, {{0, 4}}) == 44);
  for (const std::string& name : holed.names) CHECK(name != "pyramid_r0_4");
  // Row 1 has 8 boxes, 0 to 7.
  CHECK_THROWS_WITH(addPyramid(holed, PyramidSpec{9}, {{1, 8}}), Catch::Contains("(1, 8)"));
  CHECK(clumpGrid(100) == Eigen::Vector3i(5, 5, 4));
  CHECK(clumpGrid(1000) == Eigen::Vector3i(10, 10, 10));
  World c;
  addClump(c, ClumpSpec{});
  Vec3 centroid = Vec3::Zero(), momentum = Vec3::Zero();
  for (const RigidBody& b : c.bodies) {
    centroid += b.s.x / 100.0;
    momentum += b.s.P;
    CHECK(b.v.norm() == Approx(5.0));  // no cube sits exactly at the centre of a 5x5x4 grid
  }
  CHECK((centroid - Vec3(0, 20, 0)).norm() < 1e-12);
  CHECK(momentum.norm() < 1e-12);  // everything moves towards the centre
}

TEST_CASE("A spinning clump draws every spin component uniformly between minus and plus its spin, the same for the same "
          "seed", "[io][scene]") {
  ClumpSpec spec;
  spec.count = 343;
  spec.spin = 6.0;
  World a, b, other, still;
  addClump(a, spec);
  addClump(b, spec);
  addClump(still, ClumpSpec{});
  spec.seed = 2;
  addClump(other, spec);
  double largest = 0.0, mean = 0.0;
  bool differs = false;
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    CHECK(a.bodies[i].omega == b.bodies[i].omega);  // determinism: the same bits
    differs = differs || a.bodies[i].omega != other.bodies[i].omega;
    largest = std::max(largest, a.bodies[i].omega.cwiseAbs().maxCoeff());
    mean += a.bodies[i].omega.sum() / (3.0 * 343.0);
  }
  CHECK(differs);
  CHECK(largest <= 6.0);
  CHECK(largest > 5.9);  // all 1029 draws short of 5.9: probability (5.9 / 6)^1029 < 1e-7
  // The mean of 1029 uniform draws on [-6, 6] has a standard deviation of 6/sqrt(3 * 1029).
  CHECK(std::abs(mean) < 4.0 * 6.0 / std::sqrt(3.0 * 1029.0));
  for (const RigidBody& body : still.bodies) CHECK(body.omega == Vec3::Zero());
  CHECK_THAT(errorOf(R"({"builders": [{"type": "clump", "spin": -1}]})"), Contains("spin"));
}

namespace {
/// Three frames of a ground and a box, with numbers that need all 17 digits.
Trajectory threeFrames() {
  Trajectory t;
  t.meta = {{"method", "basic_colliding"}, {"seed", "7"}};
  t.bodies = {{"ground", Vec3(50, 0.5, 50), true}, {"box", Vec3(0.5, 0.25, 0.125), false}};
  for (int k = 0; k < 3; ++k) {
    TrajectoryFrame f;
    f.t = k / 60.0;
    f.kinetic = 0.1 * k + 1.0 / 3.0;
    f.potential = 9.81 / 7.0;
    f.contacts = k;
    f.events = 2 * k;
    f.bisections = 11 * k;
    f.x = {Vec3(0, -0.5, 0), Vec3(0.1, 1.0 / 3.0 + k, -2e-17)};
    f.q = {Quat::Identity(), Quat(Eigen::AngleAxisd(0.1 * k + 0.01, Vec3(1, 2, 3).normalized()))};
    t.frames.push_back(f);
  }
  return t;
}

/// The files in `dir`.
std::size_t fileCount(const std::filesystem::path& dir) {
  return static_cast<std::size_t>(std::distance(std::filesystem::directory_iterator(dir),
                                                std::filesystem::directory_iterator{}));
}

std::string contentsOf(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// An empty folder of the given name in the temporary directory, removed at the end.
class ScratchFolder {
 public:
  explicit ScratchFolder(const std::string& name)
      : path_(std::filesystem::temp_directory_path() / name) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  ~ScratchFolder() { std::filesystem::remove_all(path_); }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};
}  // namespace

TEST_CASE("Trajectory files round-trip bit for bit", "[io][trajectory]") {
  const Trajectory t = threeFrames();
  const std::string path = (std::filesystem::temp_directory_path() / "boxsim_io_test_traj.dat").string();
  writeTrajectory(path, t);
  const Trajectory r = readTrajectory(path);
  std::remove(path.c_str());
  CHECK(r.meta == t.meta);
  REQUIRE(r.frames.size() == 3);
  REQUIRE(r.bodies.size() == 2);
  CHECK(r.bodies[1].halfExtents == t.bodies[1].halfExtents);
  CHECK(r.bodies[0].immovable);
  for (int k = 0; k < 3; ++k) {
    CHECK(r.frames[k].t == t.frames[k].t);
    CHECK(r.frames[k].kinetic == t.frames[k].kinetic);
    CHECK(r.frames[k].bisections == t.frames[k].bisections);
    CHECK(r.frames[k].x[1] == t.frames[k].x[1]);
    CHECK(r.frames[k].q[1].coeffs() == t.frames[k].q[1].coeffs());
  }
}

TEST_CASE("A malformed trajectory file is rejected with file and line", "[io][trajectory][input]") {
  const std::string path = (std::filesystem::temp_directory_path() / "boxsim_io_test_bad.dat").string();
  writeFileAtomically(path, "# boxsim trajectory 1\n# body 0 box half_extents 1 1 1 immovable 0\n0 1 2\n");
  CHECK_THROWS_WITH(readTrajectory(path), Contains("boxsim_io_test_bad.dat:3:"));
  std::remove(path.c_str());
}

TEST_CASE("Files are written whole or not at all", "[io][atomic]") {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "boxsim_io_test_atomic";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "out.txt").string();
  writeFileAtomically(path, "first");
  writeFileAtomically(path, "second, longer");
  std::ifstream in(path);
  std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(content == "second, longer");
  // A folder that does not exist: an error naming the path, and nothing left behind.
  CHECK_THROWS_WITH(writeFileAtomically((dir / "missing" / "x.txt").string(), "data"),
                    Contains("missing/x.txt"));
  CHECK(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator{}) == 1);
  std::filesystem::remove_all(dir);
}

TEST_CASE("A trajectory streamed frame by frame is the file writeTrajectory writes, byte for byte, "
          "and reads back frame by frame",
          "[io][trajectory][stream]") {
  const ScratchFolder scratch("boxsim_io_test_stream");
  const std::filesystem::path& dir = scratch.path();
  const Trajectory t = threeFrames();
  const std::string whole = (dir / "whole.dat").string();
  const std::string streamed = (dir / "streamed.dat").string();
  writeTrajectory(whole, t);
  {
    TrajectoryFileWriter writer(streamed);
    CHECK(std::filesystem::exists(writer.temporaryPath()));  // made before any frame
    CHECK_FALSE(std::filesystem::exists(streamed));          // the target only at the end
    replayTrajectory(t, writer);
    CHECK(writer.temporaryPath().empty());
  }
  CHECK(contentsOf(streamed) == contentsOf(whole));
  CHECK(fileCount(dir) == 2);
  TrajectoryCollector collector;
  readTrajectory(streamed, collector);
  CHECK(formatTrajectory(collector.trajectory()) == formatTrajectory(t));
}

TEST_CASE("A streamed trajectory file that is not finished leaves no file behind, and a path "
          "that cannot be written fails before the first frame",
          "[io][trajectory][stream][atomic]") {
  const ScratchFolder scratch("boxsim_io_test_abort");
  const std::filesystem::path& dir = scratch.path();
  const std::string path = (dir / "out.dat").string();
  writeFileAtomically(path, "the earlier file");
  {
    TrajectoryFileWriter writer(path);
    const Trajectory t = threeFrames();
    writer.begin(t.meta, t.bodies);
    writer.push(t.frames[0]);
  }  // an exception would leave the same way: no finish()
  CHECK(contentsOf(path) == "the earlier file");
  CHECK(fileCount(dir) == 1);
  CHECK_THROWS_AS(TrajectoryFileWriter((dir / "missing" / "x.dat").string()), CannotCreateError);
  CHECK_THROWS_WITH(TrajectoryFileWriter((dir / "missing" / "x.dat").string()),
                    Contains("there is no folder"));
  CHECK_THROWS_WITH(TrajectoryFileWriter(dir.string()), Contains("it is a folder"));
  CHECK_THROWS_WITH(TrajectoryFileWriter("/dev/null"), Contains("not a regular file"));
  CHECK(fileCount(dir) == 1);
}

TEST_CASE("A trajectory file with a header line after its first frame is refused with the line",
          "[io][trajectory][input]") {
  const std::string path = (std::filesystem::temp_directory_path() / "boxsim_io_test_late.dat").string();
  writeFileAtomically(path, "# boxsim trajectory 1\n# body 0 box half_extents 1 1 1 immovable 0\n"
                            "0 0 0 0 0 0 0 0 0 0 1 0 0 0\n# method: damped\n");
  CHECK_THROWS_AS(readTrajectory(path), TrajectoryFormatError);
  CHECK_THROWS_WITH(readTrajectory(path), Contains("boxsim_io_test_late.dat:4: a header line after"));
  std::remove(path.c_str());
}
