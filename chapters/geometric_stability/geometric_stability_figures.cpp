// Reproduction driver of the geometric stability chapter's figures beyond the thesis (§6.3.1,
// Figs. 6.4 and 6.5): stability under load (load_stability.hpp).
//
// Writes into the output folder, each file whole or not at all: Figs. 6.4 and 6.5 rendered in
// 3D with stable boxes dark; the verdict on Fig. 6.5 against the top block's mass beside the
// accelerations of the full frictionless LCP (the brute-force answer); and, on the pyramid with
// gaps of Fig. 5.6, the settling pile and the clump at rest, how many boxes each rule finds
// stable, the analytic method's LCP size and the time of one contact-force evaluation under
// each. Timings are measurements of this machine.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "boxsim/analytic_lcp/analytic_stepper.hpp"
#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/geometric_stability/geometric_stability.hpp"
#include "boxsim/geometric_stability/load_stability.hpp"
#include "boxsim/io/atomic_file.hpp"
#include "boxsim/io/recorder.hpp"
#include "boxsim/io/render.hpp"
#include "boxsim/io/scene.hpp"
#include "boxsim/io/scene_builders.hpp"
#include "boxsim/io/simulate.hpp"
#include "boxsim/techniques.hpp"

namespace {

using namespace boxsim;

constexpr double kDt = 1.0 / 60.0;
/// m: the classifier's contact margin, as the chapter's §5.4 figures use (touching boxes count).
constexpr double kMargin = 1e-6;
/// m: the contact margin on damped integration's rest states, whose boxes rest up to the hover
/// gap g Δt² (2.7 mm at 60 Hz: its contacts are found at predicted positions) plus its contact
/// margin (0.5 mm on unit cubes) above their supports.
constexpr double kRestMargin = 3.5e-3;

/// The colours of the renders: §5.4's stable boxes dark grey as the thesis draws Fig. 5.6,
/// boxes stable under load dark blue, the others light grey.
int colourOf(char flag) {
  return flag == kGeometricallyStable ? 0x666666 : flag == kStableUnderLoad ? 0x2f4b7c : 0xd9d9d9;
}

std::vector<char> underLoadFlags(const World& world) {
  GeometricStabilityParams params;
  params.underLoad = true;
  return setGeometricallyStable(world, findContacts(world, kMargin), params);
}

/// Figs. 6.4 and 6.5 in 3D, classified under load.
void renderFigures(const std::string& out) {
  struct Figure {
    std::string stem, title;
    World world;
  };
  std::vector<Figure> figures;
  const auto add = [&figures](const std::string& stem, const std::string& title, auto build) {
    World world;
    world.addGround(0.0, 50.0);
    build(world);
    figures.push_back({stem, title, world});
  };
  add("fig6_4_staircase", "Fig. 6.4: blocks held as one heavier object (blue: stable under load)",
      [](World& w) { addFig6_4Staircase(w); });
  add("fig6_5_heavy_top", "Fig. 6.5: top 4 kg on 1 kg arms - held by its weight (blue)",
      [](World& w) { addFig6_5HeavyBridge(w, 4.0); });
  add("fig6_5_light_top", "Fig. 6.5: top 1 kg on 1 kg arms - the arms tip (light)",
      [](World& w) { addFig6_5HeavyBridge(w, 1.0); });
  for (const auto& [stem, title, world] : figures) {
    const std::vector<char> flags = underLoadFlags(world);
    Recorder recorder(world, {{"scene", stem}});
    recorder.capture(world, 0.0);
    RenderOptions options;
    options.width = 640;
    options.height = 480;
    options.title = title;
    for (std::size_t k = 0; k < world.bodies.size(); ++k)
      if (!world.bodies[k].immovable) options.bodyColours[world.names[k]] = colourOf(flags[k]);
    renderTrajectory(recorder.trajectory(), out + "/" + stem + ".png", options);
  }
}

/// Largest linear (m/s²) or angular (rad/s²) acceleration under the full frictionless LCP,
/// drift correction off: zero when everything is held.
double largestAcceleration(const World& world) {
  AnalyticParams params;
  params.driftCorrection = false;
  double largest = 0.0;
  for (const Vec3& a : AnalyticStepper(params).contactAccelerations(world, kDt))
    largest = std::max(largest, a.norm());
  return largest;
}

/// Fig. 6.5 against the top block's mass (arms of 1 kg): the verdict under load and the full
/// LCP's largest acceleration. The hand-derived threshold is a top of 2 kg.
void writeThreshold(const std::string& out) {
  std::ostringstream text;
  text << "# s6_3_fig6_5_threshold: Fig. 6.5 (addFig6_5HeavyBridge), arms 1 kg each; "
          "hand-derived threshold: top 2 kg\n"
       << "# columns: top_mass_kg stable_under_load (1: all three held) "
          "full_lcp_largest_acceleration (m/s^2 or rad/s^2)\n";
  for (int k = 1; k <= 40; ++k) {
    const double topMass = 0.125 * k;
    World world;
    world.addGround(0.0, 50.0);
    addFig6_5HeavyBridge(world, topMass);
    const std::vector<char> flags = underLoadFlags(world);
    const bool held = std::count(flags.begin(), flags.end(), kStableUnderLoad) == 3;
    char line[96];
    std::snprintf(line, sizeof line, "%.3f %d %.6e\n", topMass, held ? 1 : 0,
                  largestAcceleration(world));
    text << line;
  }
  writeFileAtomically(out + "/s6_3_fig6_5_threshold.dat", text.str());
}

/// A scene at rest: damped integration with chatter detection until every body sleeps (or
/// `limit` s), as the impulse chapter's runs of the clump and the pile settle.
World settled(const std::string& path, double limit) {
  Scene scene = loadScene(path);
  TechniqueOptions options;
  options.chatterDetection = true;
  std::unique_ptr<Stepper> stepper = makeStepper("damped", options);
  Recorder recorder(scene.world, {{"scene", path}});
  SimulateOptions run;
  run.dt = kDt;
  run.duration = limit;
  simulate(scene.world, *stepper, run, recorder);
  return scene.world;
}

/// Median of three interleaved timings (ms) of each of `work`'s modes.
template <typename Work>
std::vector<double> medianMs(int modes, Work work) {
  std::vector<std::vector<double>> samples(modes);
  for (int repetition = 0; repetition < 3; ++repetition)
    for (int m = 0; m < modes; ++m) {
      const auto start = std::chrono::steady_clock::now();
      work(m);
      samples[m].push_back(
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
  std::vector<double> medians;
  for (std::vector<double>& s : samples) {
    std::sort(s.begin(), s.end());
    medians.push_back(s[1]);
  }
  return medians;
}

/// Per scene: boxes stable under each rule, the LP's work, the analytic LCP's size under each
/// mode and the time of one contact-force evaluation (when the full LCP is small enough to
/// solve in a figure run).
void writeMeasures(const std::string& sceneDir, const std::string& out) {
  struct Case {
    std::string name;
    World world;
    double margin = kMargin;  ///< m, of the classifier and of the analytic method's contacts
  };
  std::vector<Case> cases;
  {
    World pyramid;
    pyramid.addGround(0.0, 50.0);
    // Fig. 5.6's scene, as the analytic chapter builds it: base 9, 5 cm gaps, bottom centre out.
    addPyramid(pyramid, PyramidSpec{9, 1.0, 1.0, Vec3::Zero(), 0.05}, {{0, 4}});
    cases.push_back({"pyramid_gaps", pyramid});
    World staircase, bridge;
    staircase.addGround(0.0, 50.0);
    addFig6_4Staircase(staircase);
    cases.push_back({"fig6_4", staircase});
    bridge.addGround(0.0, 50.0);
    addFig6_5HeavyBridge(bridge, 4.0);
    cases.push_back({"fig6_5_heavy", bridge});
  }
  cases.push_back({"clump100_ground_rest", settled(sceneDir + "/clump100_ground.json", 8.0), kRestMargin});
  cases.push_back({"pile343_rest", settled(sceneDir + "/pile343.json", 16.0), kRestMargin});
  // Above this many contacts a dense LCP solve takes seconds: its size is given, not its time.
  constexpr int kTimedLcpSize = 1500;

  std::ostringstream text;
  text << "# s6_3_under_load: boxes stable under the thesis' rule (§5.4) and under load, the LPs "
          "solved, and the analytic method's LCP (contacts; ms of one contact-force evaluation, "
          "median of 3 interleaved, nan: not timed) with geometric stability off, thesis, "
          "under_load\n"
       << "# rest states: damped integration with chatter detection, 8 s (clump) and 16 s (pile); "
          "contacts within " << kRestMargin << " m there (the hover gap), " << kMargin << " m elsewhere\n"
       << "# columns: scene movable stable_thesis stable_under_load lp_components lp_largest_rows "
          "lp_largest_columns lcp_off lcp_thesis lcp_under_load ms_off ms_thesis ms_under_load "
          "classify_ms_thesis classify_ms_under_load\n";
  for (const Case& c : cases) {
    const World& world = c.world;
    const std::vector<ContactManifold> contacts = findContacts(world, c.margin);
    const std::vector<char> thesis = setGeometricallyStable(world, contacts);
    std::vector<char> load = thesis;
    const LoadStabilityReport report = addStableUnderLoad(world, contacts, {}, load);
    const auto movableWith = [&world](const std::vector<char>& flags) {
      int count = 0;
      for (std::size_t k = 0; k < flags.size(); ++k) count += !world.bodies[k].immovable && flags[k];
      return count;
    };
    std::vector<AnalyticStepper> steppers;
    for (const GeometricStabilityMode mode : {GeometricStabilityMode::Off, GeometricStabilityMode::Thesis,
                                              GeometricStabilityMode::UnderLoad}) {
      AnalyticParams params;
      params.useGeometricStability = mode != GeometricStabilityMode::Off;
      params.geometricStability.underLoad = mode == GeometricStabilityMode::UnderLoad;
      params.contactMargin = std::max(params.contactMargin, c.margin);
      steppers.emplace_back(params);
    }
    std::vector<int> sizes;
    for (const AnalyticStepper& s : steppers) sizes.push_back(s.lcpSize(world));
    std::vector<double> ms(3, -1.0);
    if (sizes[0] <= kTimedLcpSize)
      ms = medianMs(3, [&](int m) { steppers[m].contactWrenches(world, kDt); });
    GeometricStabilityParams withLoad;
    withLoad.underLoad = true;
    const std::vector<double> classify = medianMs(2, [&](int m) {
      setGeometricallyStable(world, contacts, m == 0 ? GeometricStabilityParams{} : withLoad);
    });
    char line[320];
    const auto timed = [](double v) { return v < 0.0 ? std::string("nan") : std::to_string(v); };
    std::snprintf(line, sizeof line, "%s %d %d %d %d %d %d %d %d %d %s %s %s %.4f %.4f\n",
                  c.name.c_str(), world.movableCount(), movableWith(thesis), movableWith(load),
                  report.components, report.largestRows, report.largestColumns, sizes[0], sizes[1],
                  sizes[2], timed(ms[0]).c_str(), timed(ms[1]).c_str(), timed(ms[2]).c_str(),
                  classify[0], classify[1]);
    text << line;
    std::cout << "geometric_stability: " << line;
  }
  writeFileAtomically(out + "/s6_3_under_load.dat", text.str());
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Data of the geometric stability chapter's figures beyond the thesis"};
  std::string sceneDir = "chapters/impulse_damped/scenes";
  std::string out = ".";
  app.add_option("--scenes", sceneDir, "Folder of the scenes (clump100_ground.json, pile343.json)")
      ->capture_default_str();
  app.add_option("--out", out, "Folder the files are written to")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    renderFigures(out);
    writeThreshold(out);
    writeMeasures(sceneDir, out);
  } catch (const std::exception& e) {
    std::cerr << "geometric_stability_figures: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
