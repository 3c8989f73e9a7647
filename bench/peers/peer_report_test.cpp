// The peers page's comparison with an earlier page (parseBaseline, baselineComparison,
// peer_report.hpp): a
// boxsim row is worse when one of its printed measures is, rows of only one page are left out,
// and a page with no table of the tool's form is refused. The pages here are made up.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "boxsim/io/scene.hpp"
#include "peer_report.hpp"
#include "peer_run.hpp"

namespace {

using boxsim::peers::baselineComparison;
using boxsim::peers::parseBaseline;
using boxsim::peers::RunResult;
using boxsim::peers::SceneResults;

/// A page as the tool writes its table (other columns of the real page left out: the
/// comparison reads the baseline by its header's names).
const std::string kBaselineText =
    "- commit: abc1234\n\n"
    "| scene | boxes | engine | mean ms/step | penetration mean / final / max (mm) | kinetic "
    "energy at end (J) | asleep at end | all asleep from (s) |\n"
    "|---|---|---|---|---|---|---|---|\n"
    "| pile343 e=0 | 343 | boxsim damped | **2.32** | 3.9 / 0.5 / 54.3 | 0.029 | 289 | never |\n"
    "| pile343 e=0 | 343 | boxsim damped μ | **5.94** | 8.2 / 2.0 / 62.5 | 9.391 | 166 | 7.50 |\n"
    "| pile343 e=0 | 343 | Bullet 3.24 | **1.25** | 43.6 / 7.3 / 171.7 | 0.219 | 12 | never |\n"
    "| clump100 e=0 | 100 | boxsim damped | **0.65** | 0.7 / 0.5 / 7.0 | 1872.841 | 0 | never |\n";

RunResult row(const std::string& engine, double meanMm, double finalMm, double kinetic,
              double allAsleep) {
  RunResult r;
  r.engine = engine;
  r.measures.meanPenetration = meanMm / 1000.0;
  r.measures.finalPenetration = finalMm / 1000.0;
  r.measures.finalKinetic = kinetic;
  r.measures.allAsleepFrom = allAsleep;
  return r;
}

SceneResults pile(std::vector<RunResult> runs) {
  SceneResults scene;
  scene.spec.base = "pile343";
  scene.spec.restitution = 0.0;
  scene.spec.sleep = true;
  scene.runs = std::move(runs);
  return scene;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("The peers page counts a boxsim row worse than the baseline's only where a printed "
          "measure is worse",
          "[peers][report]") {
  // 3.94 mm prints as 3.9, the baseline's value: not worse. The μ row ends deeper and never
  // sleeps whole where it did from 7.50 s.
  const std::string text = baselineComparison(
      {pile({row("boxsim damped", 3.94, 0.5, 0.029, -1.0), row("boxsim damped μ", 4.6, 2.4, 0.5, -1.0),
             row("Bullet 3.24", 99.0, 99.0, 99.0, -1.0)})},
      parseBaseline(kBaselineText, "page.md"));
  CHECK(contains(text, "the page measured at abc1234"));
  CHECK(contains(text, "no worse on 1 of 2 boxsim rows"));
  CHECK(contains(text, "- pile343 e=0, boxsim damped μ: penetration mean 8.2 → 4.6 mm, final 2.0 → "
                       "2.4 mm; kinetic energy 9.391 → 0.500 J; all asleep from 7.50 → never: "
                       "**worse** (final penetration, all asleep)"));
  CHECK(contains(text, "- pile343 e=0, boxsim damped: penetration mean 3.9 → 3.9 mm, final 0.5 → "
                       "0.5 mm; kinetic energy 0.029 → 0.029 J; all asleep from never → never\n"));
  // Worse rows come first; peers and rows of one page only are left out.
  CHECK(text.find("boxsim damped μ:") < text.find("boxsim damped:"));
  CHECK_FALSE(contains(text, "Bullet"));
  CHECK_FALSE(contains(text, "clump100"));
}

TEST_CASE("The peers page compares nothing when no boxsim row is on both pages, and refuses a "
          "baseline with no table",
          "[peers][report]") {
  SceneResults clump = pile({row("boxsim damped", 1.0, 1.0, 1.0, -1.0)});
  clump.spec.base = "clump1000";
  CHECK(baselineComparison({clump}, parseBaseline(kBaselineText, "page.md")).empty());
  CHECK_THROWS_AS(parseBaseline("# a page\n\nno table here\n", "page.md"), std::invalid_argument);
}

TEST_CASE("A scene file of the user's becomes a scene of the comparison: named by its stem, at "
          "its restitution, frictionless for boxsim's plain rows, and a bad file is refused "
          "before anything runs",
          "[peers][scene-file]") {
  const std::filesystem::path dir = std::filesystem::temp_directory_path();
  const std::filesystem::path good = dir / "boxsim_peers_scene_file_test.json";
  {
    std::ofstream out(good);
    out << R"({"restitution": 0.4, "friction": 0.7, "ground": {},
      "bodies": [{"half_extents": [0.5, 0.25, 0.5], "mass": 2, "position": [0, 0.25, 0]},
                 {"half_extents": [0.2, 0.2, 0.2], "mass": 1, "position": [0, 3, -5],
                  "velocity": [0, 0, 9], "launch_time": 1}]})";
  }
  const boxsim::peers::SceneSpec spec = boxsim::peers::sceneFromFile(good.string(), 2.5);
  CHECK(spec.base == "boxsim_peers_scene_file_test");
  CHECK(spec.userFile);
  CHECK(spec.duration == 2.5);
  CHECK(spec.restitution == 0.4);
  CHECK(spec.launches);  // the second box waits for its launch: Bullet's CCD row too
  const boxsim::World world = spec.build();
  REQUIRE(world.bodies.size() == 3);  // the ground and the two boxes
  for (const boxsim::RigidBody& body : world.bodies) {
    CHECK(body.friction.muStatic == 0.0);
    CHECK(body.friction.muDynamic == 0.0);
  }
  // The boxes as the file gives them (the crate's mass and extents), not unit cubes.
  bool crate = false;
  for (const boxsim::RigidBody& body : world.bodies)
    crate = crate || (!body.immovable && body.invMass == 0.5 && body.halfExtents.y() == 0.25);
  CHECK(crate);
  std::filesystem::remove(good);

  const std::filesystem::path bad = dir / "boxsim_peers_scene_file_bad.json";
  {
    std::ofstream out(bad);
    out << R"({"bodies": [{"half_extents": [0.5, 0.5, 0.5], "mass": -1}]})";
  }
  try {
    boxsim::peers::sceneFromFile(bad.string(), 1.0);
    FAIL("a negative mass was accepted");
  } catch (const boxsim::SceneError& e) {
    CHECK(contains(e.what(), bad.string()));  // the file is named
    CHECK(contains(e.what(), "mass"));        // and the place
  }
  std::filesystem::remove(bad);
}
