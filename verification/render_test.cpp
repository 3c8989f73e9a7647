// The 3D renderer: what the gnuplot script draws, and that gnuplot turns it into whole images.
#include <stdlib.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "boxsim/io/render.hpp"

namespace {

using boxsim::Quat;
using boxsim::RenderOptions;
using boxsim::Trajectory;
using boxsim::TrajectoryBody;
using boxsim::TrajectoryFrame;
using boxsim::Vec3;

// A trajectory of the given bodies, frame f holding poses[f].
struct Pose {
  Vec3 x;
  Quat q;
};

Trajectory makeTrajectory(const std::vector<TrajectoryBody>& bodies,
                          const std::vector<std::vector<Pose>>& poses, double dt = 1.0 / 60.0) {
  Trajectory trajectory;
  trajectory.bodies = bodies;
  for (std::size_t f = 0; f < poses.size(); ++f) {
    TrajectoryFrame frame;
    frame.t = static_cast<double>(f) * dt;
    for (const Pose& pose : poses[f]) {
      frame.x.push_back(pose.x);
      frame.q.push_back(pose.q);
    }
    trajectory.frames.push_back(frame);
  }
  return trajectory;
}

TrajectoryBody ground() { return {"ground", Vec3(50.0, 0.5, 50.0), true}; }
TrajectoryBody cube(const std::string& name) { return {name, Vec3::Constant(0.5), false}; }
Pose groundPose() { return {Vec3(0.0, -0.5, 0.0), Quat::Identity()}; }

// A cube falling from 2 m onto the ground, in two frames.
Trajectory tinyDrop() {
  return makeTrajectory({ground(), cube("die")},
                        {{groundPose(), {Vec3(0.0, 2.0, 0.0), Quat::Identity()}},
                         {groundPose(), {Vec3(0.0, 0.5, 0.0), Quat::Identity()}}});
}

// The vertices of the face polygons of each frame's data block, 4 per face.
std::vector<std::vector<Vec3>> faceVertices(const std::string& script) {
  std::vector<std::vector<Vec3>> frames;
  std::istringstream in(script);
  std::string line;
  bool inBlock = false;
  while (std::getline(in, line)) {
    if (line == "$frame << EOD") {
      inBlock = true;
      frames.emplace_back();
    } else if (line == "EOD") {
      inBlock = false;
    } else if (inBlock && !line.empty()) {
      std::istringstream fields(line);
      double x = 0.0, y = 0.0, z = 0.0;
      fields >> x >> y >> z;
      if (fields) frames.back().push_back(Vec3(x, y, z));
    }
  }
  return frames;
}

// The faces of the first frame with their fill colours: data set i of the block is drawn with
// the i-th `fc rgb '#rrggbb'` of the splot command.
struct ColouredFace {
  int rgb = 0;
  std::vector<Vec3> corners;
};

std::vector<ColouredFace> colouredFaces(const std::string& script) {
  const std::size_t begin = script.find("$frame << EOD\n");
  const std::size_t end = script.find("EOD\n", begin + 14);
  std::vector<std::vector<std::vector<Vec3>>> sets(1);
  std::istringstream in(script.substr(begin + 14, end - begin - 14));
  std::string line;
  int blanks = 0;
  while (std::getline(in, line)) {
    if (line.empty()) {
      if (++blanks == 2) sets.emplace_back();
      continue;
    }
    if (blanks > 0 || sets.back().empty()) sets.back().emplace_back();
    blanks = 0;
    std::istringstream fields(line);
    double x = 0.0, y = 0.0, z = 0.0;
    fields >> x >> y >> z;
    sets.back().back().push_back(Vec3(x, y, z));
  }
  while (!sets.empty() && sets.back().empty()) sets.pop_back();
  // The splot command runs over continuation lines ending in a backslash.
  std::size_t splotEnd = script.find("\nsplot $frame", end) + 1;
  while (script[script.find('\n', splotEnd) - 1] == '\\')
    splotEnd = script.find('\n', splotEnd) + 1;
  splotEnd = script.find('\n', splotEnd);
  std::vector<int> colours;
  for (std::size_t at = script.find("fc rgb '#", end); at < splotEnd;
       at = script.find("fc rgb '#", at + 1)) {
    colours.push_back(std::stoi(script.substr(at + 9, 6), nullptr, 16));
  }
  std::vector<ColouredFace> faces;
  for (std::size_t i = 0; i < sets.size() && i < colours.size(); ++i) {
    for (const std::vector<Vec3>& polygon : sets[i]) faces.push_back({colours[i], polygon});
  }
  return faces;
}

double brightness(int rgb) { return ((rgb >> 16) & 0xff) + ((rgb >> 8) & 0xff) + (rgb & 0xff); }

int countOccurrences(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

std::string lineStartingWith(const std::string& script, const std::string& prefix) {
  std::istringstream in(script);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(prefix, 0) == 0) return line;
  }
  return "";
}

// A fresh directory under the system's temporary directory, removed at the end of the test.
class ScratchDirectory {
 public:
  ScratchDirectory() {
    std::string pattern =
        (std::filesystem::temp_directory_path() / "boxsim-render-test-XXXXXX").string();
    std::vector<char> buffer(pattern.begin(), pattern.end());
    buffer.push_back('\0');
    REQUIRE(::mkdtemp(buffer.data()) != nullptr);
    path_ = buffer.data();
  }
  ~ScratchDirectory() { std::filesystem::remove_all(path_); }
  const std::filesystem::path& path() const { return path_; }
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(path_)) {
      names.push_back(entry.path().filename().string());
    }
    std::sort(names.begin(), names.end());
    return names;
  }

 private:
  std::filesystem::path path_;
};

std::string readBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Sets an environment variable for the lifetime of this object.
class EnvironmentOverride {
 public:
  EnvironmentOverride(const char* name, const std::string& value) : name_(name) {
    const char* old = std::getenv(name);
    if (old != nullptr) old_ = old;
    hadOld_ = old != nullptr;
    ::setenv(name, value.c_str(), 1);
  }
  ~EnvironmentOverride() {
    if (hadOld_) {
      ::setenv(name_, old_.c_str(), 1);
    } else {
      ::unsetenv(name_);
    }
  }

 private:
  const char* name_;
  std::string old_;
  bool hadOld_ = false;
};

}  // namespace

TEST_CASE("An axis-aligned box shows the camera exactly three faces", "[render][geometry]") {
  const Trajectory one = makeTrajectory({ground(), cube("a")},
                                        {{groundPose(), {Vec3(0.0, 0.5, 0.0), Quat::Identity()}}});
  const std::vector<std::vector<Vec3>> frames =
      faceVertices(boxsim::renderScript(one, "a.png", {}));
  REQUIRE(frames.size() == 1);
  CHECK(frames[0].size() == 3 * 4);

  // The ground is not a box but one polygon behind everything; a small immovable box is a box.
  const Trajectory withStep =
      makeTrajectory({ground(), cube("a"), {"step", Vec3(0.5, 0.2, 0.5), true}},
                     {{groundPose(),
                       {Vec3(0.0, 0.5, 0.0), Quat::Identity()},
                       {Vec3(2.0, 0.2, 0.0), Quat::Identity()}}});
  const std::string script = boxsim::renderScript(withStep, "a.png", {});
  CHECK(faceVertices(script)[0].size() == 2 * 3 * 4);
  CHECK(countOccurrences(script, "set object 1 polygon") == 1);
}

TEST_CASE("Faces are Lambert-shaded from above: the top of a box is its brightest face",
          "[render][shading]") {
  const Trajectory one = makeTrajectory({ground(), cube("a")},
                                        {{groundPose(), {Vec3(0.0, 0.5, 0.0), Quat::Identity()}}});
  const std::vector<ColouredFace> faces = colouredFaces(boxsim::renderScript(one, "a.png", {}));
  REQUIRE(faces.size() == 3);
  const auto isTop = [](const ColouredFace& face) {
    return std::all_of(face.corners.begin(), face.corners.end(),
                       [](const Vec3& p) { return std::abs(p.z() - 1.0) < 1e-6; });
  };
  const auto top = std::find_if(faces.begin(), faces.end(), isTop);
  REQUIRE(top != faces.end());
  for (const ColouredFace& face : faces) {
    REQUIRE(face.corners.size() == 4);
    if (&face != &*top) CHECK(brightness(face.rgb) < brightness(top->rgb));
  }
  // The light is oblique, so the two sides in view get two different shades.
  CHECK(faces[0].rgb != faces[1].rgb);
  CHECK(faces[1].rgb != faces[2].rgb);
  CHECK(faces[0].rgb != faces[2].rgb);
}

TEST_CASE("Bodies named in bodyColours are filled with their colour, and an unknown name is "
          "refused",
          "[render][shading]") {
  // Two cubes side by side, "dark" given a dark grey: its three faces are shades of that grey
  // (equal channels, no channel above the unshaded 0x40), the other keeps the palette.
  const Trajectory two = makeTrajectory(
      {ground(), cube("dark"), cube("light")},
      {{groundPose(), {Vec3(-1.0, 0.5, 0.0), Quat::Identity()}, {Vec3(1.0, 0.5, 0.0), Quat::Identity()}}});
  RenderOptions options;
  options.bodyColours = {{"dark", 0x404040}};
  const std::vector<ColouredFace> faces = colouredFaces(boxsim::renderScript(two, "a.png", options));
  REQUIRE(faces.size() == 6);
  int grey = 0;
  for (const ColouredFace& face : faces) {
    const int r = (face.rgb >> 16) & 0xff, g = (face.rgb >> 8) & 0xff, b = face.rgb & 0xff;
    if (r == g && g == b && r <= 0x40) ++grey;
  }
  CHECK(grey == 3);
  options.bodyColours = {{"dsrk", 0x404040}};
  try {
    boxsim::renderScript(two, "a.png", options);
    FAIL("an unknown body name was accepted");
  } catch (const std::invalid_argument& e) {
    CHECK(std::string(e.what()).find("'dsrk'") != std::string::npos);
  }
}

TEST_CASE("A box in any orientation shows three faces, never two opposite ones",
          "[render][geometry]") {
  // Under an orthographic camera exactly one of each pair of opposite faces points at the
  // viewer, unless a face is seen edge-on (probability zero for random orientations).
  std::mt19937 random(20030501);
  std::normal_distribution<double> gauss;
  std::vector<std::vector<Pose>> poses;
  for (int f = 0; f < 50; ++f) {
    const Quat q = Quat(gauss(random), gauss(random), gauss(random), gauss(random)).normalized();
    poses.push_back({groundPose(), {Vec3(0.0, 2.0, 0.0), q}, {Vec3(3.0, 1.0, 1.0), q.inverse()}});
  }
  const Trajectory spinning = makeTrajectory({ground(), cube("a"), cube("b")}, poses);
  RenderOptions options;
  for (int f = 0; f < 50; ++f) options.frames.push_back(f);
  const std::vector<std::vector<Vec3>> frames =
      faceVertices(boxsim::renderScript(spinning, "strip.svg", options));
  REQUIRE(frames.size() == 50);
  for (const std::vector<Vec3>& vertices : frames) CHECK(vertices.size() == 2 * 3 * 4);
}

TEST_CASE("World y-up is drawn z-up: (x, y, z) goes to gnuplot (x, -z, y)", "[render][geometry]") {
  const Trajectory lifted = makeTrajectory(
      {ground(), cube("a")}, {{groundPose(), {Vec3(1.0, 2.0, 3.0), Quat::Identity()}}});
  const std::vector<Vec3> vertices = faceVertices(boxsim::renderScript(lifted, "a.png", {}))[0];
  REQUIRE(vertices.size() == 12);
  for (const Vec3& v : vertices) {
    CHECK(v.x() == Approx(1.0).margin(0.5 + 1e-6));
    CHECK(v.y() == Approx(-3.0).margin(0.5 + 1e-6));
    CHECK(v.z() == Approx(2.0).margin(0.5 + 1e-6));
  }
  // The camera looks from above, from +x and from +z (world): the visible faces are the top
  // (gnuplot z = 2.5), the +x face (x = 1.5) and the +z face (gnuplot y = -3.5).
  const auto faceWhere = [&](int axis, double value) {
    for (std::size_t face = 0; face < 3; ++face) {
      bool all = true;
      for (std::size_t i = 0; i < 4; ++i)
        all = all && std::abs(vertices[4 * face + i][axis] - value) < 1e-6;
      if (all) return true;
    }
    return false;
  };
  CHECK(faceWhere(2, 2.5));
  CHECK(faceWhere(0, 1.5));
  CHECK(faceWhere(1, -3.5));
}

TEST_CASE("Every frame is drawn with the same camera and ranges", "[render][camera]") {
  const Trajectory drop = tinyDrop();
  RenderOptions first;
  first.frames = {0};
  RenderOptions second;
  second.frames = {1};
  const std::string a = boxsim::renderScript(drop, "a.png", first);
  const std::string b = boxsim::renderScript(drop, "a.png", second);
  for (const char* prefix : {"set xrange", "set yrange", "set zrange", "set view "}) {
    CHECK(!lineStartingWith(a, prefix).empty());
    CHECK(lineStartingWith(a, prefix) == lineStartingWith(b, prefix));
  }
  CHECK(a.find("set view equal xyz") != std::string::npos);
}

TEST_CASE("Several frames in a PNG make a strip of panels titled with their times",
          "[render][layout]") {
  const Trajectory drop = tinyDrop();
  RenderOptions options;
  options.frames = {0, 1, 1};
  const std::string script = boxsim::renderScript(drop, "strip.png", options);
  CHECK(script.find("size 2400,600") != std::string::npos);
  CHECK(script.find("set multiplot") != std::string::npos);
  CHECK(countOccurrences(script, "'t = 0.00 s'") == 1);
  CHECK(countOccurrences(script, "'t = 0.02 s'") == 2);
  CHECK(countOccurrences(script, "\nsplot ") == 3);
}

TEST_CASE("A GIF is subsampled to at most maxGifFrames at real-time delays", "[render][gif]") {
  std::vector<std::vector<Pose>> poses(1000,
                                       {groundPose(), {Vec3(0.0, 0.5, 0.0), Quat::Identity()}});
  const Trajectory long100Hz = makeTrajectory({ground(), cube("a")}, poses, 0.01);
  const std::string script = boxsim::renderScript(long100Hz, "run.gif", {});
  // 1000 frames 0.01 s apart, at most 200: every 5th frame, 0.05 s = 5/100 s apart.
  CHECK(script.find("animate delay 5 ") != std::string::npos);
  CHECK(countOccurrences(script, "\nsplot ") == 200);

  // 1/60 s frames cannot be shown at real time one by one (GIF delays are whole 1/100 s and
  // browsers slow down delays under 2/100 s); every third frame, 5/100 s apart, is exact.
  poses.resize(120);
  const Trajectory short60Hz = makeTrajectory({ground(), cube("a")}, poses, 1.0 / 60.0);
  const std::string shortScript = boxsim::renderScript(short60Hz, "run.gif", {});
  CHECK(shortScript.find("animate delay 5 ") != std::string::npos);
  CHECK(countOccurrences(shortScript, "\nsplot ") == 40);

  RenderOptions fixedDelay;
  fixedDelay.gifDelaySeconds = 0.25;
  fixedDelay.maxGifFrames = 30;
  const std::string slow = boxsim::renderScript(short60Hz, "run.gif", fixedDelay);
  CHECK(slow.find("animate delay 25 ") != std::string::npos);
  CHECK(countOccurrences(slow, "\nsplot ") == 30);
}

TEST_CASE("An unknown image extension is refused, naming it and the supported ones",
          "[render][errors]") {
  const Trajectory drop = tinyDrop();
  CHECK_THROWS_AS(boxsim::renderScript(drop, "picture.jpg", {}), std::invalid_argument);
  CHECK_THROWS_WITH(boxsim::renderScript(drop, "picture.jpg", {}),
                    Catch::Contains(".jpg") && Catch::Contains(".png") && Catch::Contains(".gif") &&
                        Catch::Contains(".svg"));
  CHECK_THROWS_AS(boxsim::renderScript(drop, "no_extension", {}), std::invalid_argument);
  ScratchDirectory scratch;
  CHECK_THROWS_AS(boxsim::renderTrajectory(drop, (scratch.path() / "x.bmp").string(), {}),
                  std::invalid_argument);
  CHECK(scratch.entries().empty());
}

TEST_CASE("A frame index outside the trajectory is refused, naming the valid range",
          "[render][errors]") {
  const Trajectory drop = tinyDrop();
  RenderOptions options;
  options.frames = {0, 2};
  CHECK_THROWS_AS(boxsim::renderScript(drop, "a.png", options), std::out_of_range);
  CHECK_THROWS_WITH(boxsim::renderScript(drop, "a.png", options), Catch::Contains("0..1"));
  options.frames = {-1};
  CHECK_THROWS_WITH(boxsim::renderScript(drop, "a.gif", options), Catch::Contains("0..1"));
  ScratchDirectory scratch;
  CHECK_THROWS_AS(boxsim::renderTrajectory(drop, (scratch.path() / "a.png").string(), options),
                  std::out_of_range);
  CHECK(scratch.entries().empty());
}

TEST_CASE("Rendering writes whole PNG, GIF and SVG files and no temporary file",
          "[render][gnuplot]") {
  const Trajectory drop = tinyDrop();
  ScratchDirectory scratch;
  RenderOptions options;
  options.width = 320;
  options.height = 240;
  options.title = "A die's drop";  // a quote, which the script must escape
  boxsim::renderTrajectory(drop, (scratch.path() / "drop.png").string(), options);
  boxsim::renderTrajectory(drop, (scratch.path() / "drop.gif").string(), options);
  boxsim::renderTrajectory(drop, (scratch.path() / "drop.svg").string(), options);
  options.frames = {0, 1};
  boxsim::renderTrajectory(drop, (scratch.path() / "strip.png").string(), options);

  CHECK(scratch.entries() ==
        std::vector<std::string>{"drop.gif", "drop.png", "drop.svg", "strip.png"});
  const std::string png = readBytes(scratch.path() / "drop.png");
  const std::string gif = readBytes(scratch.path() / "drop.gif");
  const std::string svg = readBytes(scratch.path() / "drop.svg");
  const std::string strip = readBytes(scratch.path() / "strip.png");
  CHECK(png.rfind("\x89PNG\r\n\x1a\n", 0) == 0);
  CHECK(strip.rfind("\x89PNG\r\n\x1a\n", 0) == 0);
  CHECK(gif.rfind("GIF89a", 0) == 0);
  CHECK(svg.find("<svg") != std::string::npos);
  CHECK(png.size() > 1000);
  CHECK(gif.size() > 1000);
  // PNG IHDR: width and height, big-endian, at bytes 16..23.
  const auto be32 = [](const std::string& bytes, std::size_t at) {
    return (static_cast<unsigned char>(bytes[at]) << 24) |
           (static_cast<unsigned char>(bytes[at + 1]) << 16) |
           (static_cast<unsigned char>(bytes[at + 2]) << 8) |
           static_cast<unsigned char>(bytes[at + 3]);
  };
  CHECK(be32(png, 16) == 320u);
  CHECK(be32(png, 20) == 240u);
  CHECK(be32(strip, 16) == 640u);
}

TEST_CASE("A failing gnuplot leaves the old image untouched and reports its error output",
          "[render][gnuplot][errors]") {
  ScratchDirectory scratch;
  const std::filesystem::path fake = scratch.path() / "fake-gnuplot";
  {
    std::ofstream script(fake);
    script << "#!/bin/sh\necho 'line 7: simulated failure' >&2\nexit 1\n";
  }
  std::filesystem::permissions(fake, std::filesystem::perms::owner_all);
  const std::filesystem::path image = scratch.path() / "old.png";
  {
    std::ofstream old(image);
    old << "previous picture";
  }
  {
    EnvironmentOverride useFake("BOXSIM_GNUPLOT", fake.string());
    CHECK_THROWS_AS(boxsim::renderTrajectory(tinyDrop(), image.string(), {}), std::runtime_error);
    CHECK_THROWS_WITH(boxsim::renderTrajectory(tinyDrop(), image.string(), {}),
                      Catch::Contains("simulated failure"));
  }
  CHECK(readBytes(image) == "previous picture");
  CHECK(scratch.entries() == std::vector<std::string>{"fake-gnuplot", "old.png"});

  EnvironmentOverride missing("BOXSIM_GNUPLOT", (scratch.path() / "no-such-gnuplot").string());
  CHECK_THROWS_AS(boxsim::renderTrajectory(tinyDrop(), (scratch.path() / "new.gif").string(), {}),
                  std::runtime_error);
  CHECK(scratch.entries() == std::vector<std::string>{"fake-gnuplot", "old.png"});
}
