/// \file
/// boxsim side by side with Bullet and ODE: the same scenes, in one process, one thread,
/// Δt = 1/60 s, 1 kg unit cubes. For each scene and engine it times every step and measures
/// the result with one yardstick (boxsim's separating-axis test on each engine's poses), then
/// prints a table and writes it as Markdown (and, with --scaling, the data of the scaling
/// figure).
///
/// Usage: `build/bench/boxsim_peers [--scene die] [--engine damped --engine bullet] [--quick]
/// [--table peers.md] [--scaling scaling.dat]`. Bullet and ODE take part when their Debian
/// packages (libbullet-dev, libode-dev) were found at configure time; the table says which
/// were absent.
///
/// Columns: ms per step, median and 95th percentile over the run's steps (wall clock, the
/// engine's step alone); steps per second (1000 / mean ms); the deepest penetration between
/// any two boxes (box-ground included) over the run; the kinetic energy left at the end; the
/// drift of the tower's top box from its start; the frame from which the die stays at rest
/// (speed < 1 cm/s and spin < 0.02 rad/s up to the end). The ratio compares boxsim's damped
/// integration with each peer in the same run: peer ms / boxsim ms, above 1 when boxsim is
/// faster.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/io/atomic_file.hpp"
#include "boxsim/io/scene.hpp"
#include "boxsim/io/scene_builders.hpp"
#include "peer_engine.hpp"

namespace boxsim::peers {
namespace {

constexpr double kDt = 1.0 / 60.0;
/// The die counts as at rest below these (a 1 kg unit cube: 5e-5 J of translation).
constexpr double kRestSpeed = 0.01;   // m/s
constexpr double kRestSpin = 0.02;    // rad/s
/// Scenes with more boxes are measured (penetration) every this many frames, to keep the
/// harness's own measuring from dominating its run time; timing is unaffected.
constexpr int kMeasureEveryLarge = 10;
constexpr std::size_t kLargeScene = 2000;

/// A scene of the comparison: how to build it and how long to run it.
struct SceneSpec {
  std::string name;
  double duration = 5.0;  ///< s
  std::function<World()> build;
  bool tower = false;  ///< track the top box's drift
  bool die = false;    ///< report when the die comes to rest
};

World fromFile(const std::string& stem) {
  return loadScene(std::string(BOXSIM_SCENE_DIR) + "/" + stem + ".json").world;
}

World clump(int count) {
  World world;
  world.addGround(0.0, 150.0, 0.5);
  ClumpSpec spec;
  spec.count = count;
  addClump(world, spec);
  return world;
}

std::vector<SceneSpec> comparisonScenes() {
  return {
      {"die", 10.0, [] { return fromFile("die"); }, false, true},
      {"tower10", 10.0, [] { return fromFile("tower10"); }, true, false},
      {"pyramid10_shot", 8.0, [] { return fromFile("pyramid10_shot"); }, false, false},
      {"pyramid20_shot", 8.0, [] { return fromFile("pyramid20_shot"); }, false, false},
      {"clump100", 8.0, [] { return clump(100); }, false, false},
      {"clump1000", 6.0, [] { return clump(1000); }, false, false},
      {"clump10000", 3.0, [] { return clump(10000); }, false, false},
  };
}

/// What one engine did on one scene.
struct RunResult {
  std::string scene;
  std::string engine;
  int bodies = 0;  ///< movable boxes
  long steps = 0;
  double medianMs = 0, p95Ms = 0, meanMs = 0;
  double deepestPenetration = 0;  ///< m
  double finalKinetic = 0;        ///< J
  double trackedDrift = std::numeric_limits<double>::quiet_NaN();  ///< m
  long restFrame = -2;  ///< -2: not a die scene; -1: never at rest
};

double kineticEnergy(const World& mirror, const std::vector<PeerPose>& poses) {
  double e = 0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const RigidBody& b = mirror.bodies[i];
    if (b.immovable) continue;
    const Vec3 inertia = boxInertiaDiagonal(b.halfExtents, b.mass);
    const Vec3 w = poses[i].q.conjugate() * poses[i].omega;  // body frame
    e += 0.5 * b.mass * poses[i].v.squaredNorm() + 0.5 * w.dot(inertia.cwiseProduct(w));
  }
  return e;
}

RunResult runOne(const SceneSpec& spec, PeerEngine& engine) {
  PeerScene scene = peerSceneFromWorld(spec.name, spec.build(), spec.duration);
  World mirror = scene.world;  // poses go in here to be measured with boxsim's own tests
  mirror.applyLaunches(std::numeric_limits<double>::infinity());
  engine.load(scene);
  const long steps = std::lround(spec.duration / kDt);
  const int every = scene.boxes.size() > kLargeScene ? kMeasureEveryLarge : 1;
  int die = -1;  // the scene's first movable body, when it is the die
  for (std::size_t i = 0; spec.die && die < 0 && i < mirror.bodies.size(); ++i)
    if (!mirror.bodies[i].immovable) die = static_cast<int>(i);
  const int top = spec.tower ? static_cast<int>(mirror.bodies.size()) - 1 : -1;
  const Vec3 topStart = top >= 0 ? scene.boxes[static_cast<std::size_t>(top)].x : Vec3::Zero();

  RunResult r;
  r.scene = spec.name;
  r.engine = engine.name();
  r.bodies = mirror.movableCount();
  r.steps = steps;
  std::vector<double> ms;
  ms.reserve(static_cast<std::size_t>(steps));
  std::vector<PeerPose> poses;
  long lastMoving = -1;
  for (long k = 1; k <= steps; ++k) {
    const auto start = std::chrono::steady_clock::now();
    engine.step(kDt, static_cast<double>(k - 1) * kDt);
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    const bool measure = k % every == 0 || k == steps;
    if (!measure && die < 0) continue;
    engine.read(poses);
    if (die >= 0) {
      const PeerPose& p = poses[static_cast<std::size_t>(die)];
      if (p.v.norm() >= kRestSpeed || p.omega.norm() >= kRestSpin) lastMoving = k;
    }
    if (!measure) continue;
    for (std::size_t i = 0; i < poses.size(); ++i) {
      mirror.bodies[i].s.x = poses[i].x;
      mirror.bodies[i].s.q = poses[i].q.normalized();
      mirror.bodies[i].updateDerived();
    }
    r.deepestPenetration = std::max(r.deepestPenetration, deepestPenetration(mirror));
  }
  engine.read(poses);
  r.finalKinetic = kineticEnergy(mirror, poses);
  if (top >= 0) r.trackedDrift = (poses[static_cast<std::size_t>(top)].x - topStart).norm();
  if (die >= 0) r.restFrame = lastMoving < steps ? lastMoving + 1 : -1;
  std::vector<double> sorted = ms;
  std::sort(sorted.begin(), sorted.end());
  r.medianMs = sorted[sorted.size() / 2];
  r.p95Ms = sorted[std::min(sorted.size() - 1, static_cast<std::size_t>(0.95 * static_cast<double>(sorted.size())))];
  double sum = 0;
  for (double m : ms) sum += m;
  r.meanMs = sum / static_cast<double>(ms.size());
  return r;
}

std::unique_ptr<PeerEngine> makeEngine(const std::string& name) {
#ifdef BOXSIM_HAVE_BULLET
  if (name == "bullet") return makeBulletEngine();
#endif
#ifdef BOXSIM_HAVE_ODE
  if (name == "ode") return makeOdeEngine();
#endif
  if (name == "bullet" || name == "ode")
    throw std::invalid_argument("engine '" + name + "' was not found at configure time; install lib" +
                                (name == "ode" ? std::string("ode") : std::string("bullet")) +
                                "-dev and configure again");
  return makeBoxsimEngine(name);
}

std::string fixed(double value, int digits) {
  if (std::isnan(value)) return "–";
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", digits, value);
  return text;
}

std::string markdownTable(const std::vector<RunResult>& results,
                          const std::map<std::string, std::string>& settings,
                          const std::string& absent) {
  std::ostringstream out;
  out << "| scene | boxes | engine | ms/step median | ms/step p95 | steps/s | deepest penetration (mm) "
         "| kinetic energy at end (J) | tower top drift (mm) | die at rest from frame | peer ms / boxsim damped ms |\n"
      << "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const RunResult& r : results) {
    double boxsimMs = std::numeric_limits<double>::quiet_NaN();
    for (const RunResult& o : results)
      if (o.scene == r.scene && o.engine == "boxsim damped") boxsimMs = o.medianMs;
    const bool peer = r.engine.rfind("boxsim", 0) != 0;
    out << "| " << r.scene << " | " << r.bodies << " | " << r.engine << " | " << fixed(r.medianMs, 3)
        << " | " << fixed(r.p95Ms, 3) << " | " << fixed(1000.0 / r.meanMs, 0) << " | "
        << fixed(1000.0 * r.deepestPenetration, 2) << " | " << fixed(r.finalKinetic, 4) << " | "
        << fixed(1000.0 * r.trackedDrift, 2) << " | "
        << (r.restFrame == -2 ? "–" : r.restFrame == -1 ? "never" : std::to_string(r.restFrame))
        << " | " << (peer ? fixed(r.medianMs / boxsimMs, 2) : "") << " |\n";
  }
  out << "\nEngines:\n";
  for (const auto& [name, text] : settings) out << "- " << name << ": " << text << "\n";
  if (!absent.empty()) out << "- not found at configure time: " << absent << "\n";
  return out.str();
}

}  // namespace
}  // namespace boxsim::peers

int main(int argc, char** argv) {
  using namespace boxsim::peers;
  CLI::App app("boxsim side by side with Bullet and ODE on the thesis' scenes");
  std::vector<std::string> sceneNames;
  std::vector<std::string> engineNames;
  std::string tablePath;
  std::string scalingPath;
  double durationScale = 1.0;
  app.add_option("--scene", sceneNames, "Scene to run (repeatable; default: all)");
  app.add_option("--engine", engineNames,
                 "Engine (repeatable): a boxsim method (damped, impulse, ...), optionally with "
                 "a contact gathering after a slash (damped/every_pass), bullet, ode "
                 "(default: damped, impulse and every peer found)");
  app.add_option("--table", tablePath, "Write the table here as Markdown");
  app.add_option("--scaling", scalingPath,
                 "Instead of the table: time clumps of 100 to 10000 cubes for 3 s (times "
                 "--duration-scale) under damped integration and every peer found, and write "
                 "the data of the scaling figure here");
  app.add_option("--duration-scale", durationScale, "Multiply every scene's duration (e.g. 0.1 for a quick look)")
      ->check(CLI::PositiveNumber);
  CLI11_PARSE(app, argc, argv);

  std::string absent;
  if (engineNames.empty()) {
    // The scaling figure compares the default technique with the peers; the table shows both.
    engineNames = {"damped"};
    if (scalingPath.empty()) engineNames.push_back("impulse");
#ifdef BOXSIM_HAVE_BULLET
    engineNames.push_back("bullet");
#else
    absent += "Bullet (libbullet-dev) ";
#endif
#ifdef BOXSIM_HAVE_ODE
    engineNames.push_back("ode");
#else
    absent += "ODE (libode-dev) ";
#endif
  }
  try {
    std::vector<SceneSpec> scenes = comparisonScenes();
    if (!scalingPath.empty()) {
      scenes.clear();
      for (int n : {100, 300, 1000, 3000, 10000})
        scenes.push_back({"clump" + std::to_string(n), 3.0, [n] { return clump(n); }, false, false});
    } else if (!sceneNames.empty()) {
      std::vector<SceneSpec> chosen;
      for (const std::string& name : sceneNames) {
        auto it = std::find_if(scenes.begin(), scenes.end(), [&](const SceneSpec& s) { return s.name == name; });
        if (it == scenes.end()) throw std::invalid_argument("unknown scene '" + name + "'");
        chosen.push_back(*it);
      }
      scenes = chosen;
    }
    std::vector<RunResult> results;
    std::map<std::string, std::string> settings;
    for (SceneSpec& spec : scenes) {
      spec.duration *= durationScale;
      for (const std::string& name : engineNames) {
        std::unique_ptr<PeerEngine> engine = makeEngine(name);
        settings[engine->name()] = engine->settings();
        results.push_back(runOne(spec, *engine));
        const RunResult& r = results.back();
        std::fprintf(stderr, "%-15s %-16s %9.3f ms median %9.3f ms p95  pen %.2f mm  KE %.4f J\n",
                     r.scene.c_str(), r.engine.c_str(), r.medianMs, r.p95Ms,
                     1000 * r.deepestPenetration, r.finalKinetic);
      }
    }
    const std::string table = markdownTable(results, settings, absent);
    std::cout << table;
    if (!tablePath.empty()) boxsim::writeFileAtomically(tablePath, table);
    if (!scalingPath.empty()) {
      std::ostringstream dat;
      dat << "# s7_peers_scaling: ms per step (median and 95th percentile over the first "
          << 3.0 * durationScale << " s) against cubes in the clump of Fig. 6.7\n"
          << "# dt: " << kDt << "\n# columns: boxes engine median_ms p95_ms\n";
      for (const RunResult& r : results)
        dat << r.bodies << " \"" << r.engine << "\" " << r.medianMs << " " << r.p95Ms << "\n";
      boxsim::writeFileAtomically(scalingPath, dat.str());
    }
  } catch (const std::exception& e) {
    std::cerr << "boxsim_peers: error: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
