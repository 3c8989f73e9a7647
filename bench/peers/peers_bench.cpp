/// \file
/// boxsim side by side with Bullet and ODE: the same scenes, in one process, one thread,
/// Δt = 1/60 s, 1 kg unit cubes, every scene repeated and the engines interleaved. Writes the
/// Markdown page docs/benchmarks.md (peer_report.hpp says what it holds) and the data of the
/// scaling figure; with `--impact page.md`, the shot pyramids' impact with friction under every
/// engine instead (docs/shot_impact.md, peer_impact.hpp).
///
/// Usage: `build/bench/boxsim_peers [--scene clump1000] [--engine damped --engine bullet]
/// [--restitution 0] [--sleep on|off] [--perturb 1] [--reps 3] [--table page.md] [--scaling scaling.dat]`.
/// Bullet and ODE take part when their Debian packages (libbullet-dev, libode-dev) were found
/// at configure time; the page says which were absent.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <numeric>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "boxsim/core/random.hpp"
#include "boxsim/io/atomic_file.hpp"
#include "boxsim/io/scene.hpp"
#include "boxsim/io/scene_builders.hpp"
#include "peer_impact.hpp"
#include "peer_report.hpp"
#include "peer_run.hpp"

namespace boxsim::peers {
namespace {

World fromFile(const std::string& stem) {
  return loadScene(std::string(BOXSIM_SCENE_DIR) + "/" + stem + ".json").world;
}

/// What --perturb adds to each component of every movable body's starting velocity: at most
/// 1 µm/s, far below anything a scene's physics or its measures resolve, enough to change
/// every bit of a chaotic trajectory after a few collisions.
constexpr double kPerturbation = 1e-6;

/// `world` with every movable body's velocity nudged by a seeded random vector, each component
/// uniform in ±kPerturbation m/s (core/random.hpp's stream of `seed`); 0 leaves it as it is.
World perturbed(World world, unsigned long seed) {
  if (seed == 0) return world;
  UniformRandom random(seed);
  for (RigidBody& body : world.bodies) {
    if (body.immovable) continue;
    Vec3 nudge;
    for (int k = 0; k < 3; ++k) nudge[k] = kPerturbation * (2.0 * random.next() - 1.0);
    body.setVelocity(body.v + nudge);
  }
  return world;
}

World clump(int count) {
  World world;
  world.addGround(0.0, 150.0, 0.5);
  ClumpSpec spec;
  spec.count = count;
  addClump(world, spec);
  return world;
}

/// Seconds each clump runs: flight, the cubes meeting in mid-air, and their impact on the
/// ground (the 10 000-cube clump's lowest layer lands at once and piles up). One length for
/// every size, for the scaling figure; 2 s keeps the whole comparison (three repetitions)
/// under ten minutes, most of it the 10 000-cube clump at restitution 0. The settling pile
/// (pile343) is the scene that settles.
constexpr double kClumpSeconds = 2.0;

/// Every scene of the default comparison, in the order of the page.
std::vector<SceneSpec> comparisonScenes() {
  std::vector<SceneSpec> scenes;
  auto add = [&](const std::string& base, double seconds, std::function<World()> build,
                 std::vector<double> restitutions, std::vector<bool> sleeps = {true}) {
    for (double e : restitutions)
      for (bool sleep : sleeps) {
        SceneSpec spec;
        spec.base = base;
        spec.duration = seconds;
        spec.build = build;
        spec.restitution = e;
        spec.sleep = sleep;
        spec.die = base == "die";
        spec.tower = base == "tower10";
        spec.launches = base.find("_shot") != std::string::npos;
        scenes.push_back(spec);
      }
  };
  add("die", 10.0, [] { return fromFile("die"); }, {0.9, 0.0});
  add("tower10", 10.0, [] { return fromFile("tower10"); }, {0.9});
  add("pyramid10_shot", 8.0, [] { return fromFile("pyramid10_shot"); }, {0.9}, {true, false});
  add("pyramid20_shot", 8.0, [] { return fromFile("pyramid20_shot"); }, {0.9}, {true, false});
  add("pile343", 8.0, [] { return fromFile("pile343"); }, {0.0, 0.9});
  // A stack that §5.4's rule does not hold (its faces overhang) and its loads do.
  add("stack20_offset", 8.0, [] { return fromFile("stack20_offset"); }, {0.0});
  add("clump100", kClumpSeconds, [] { return clump(100); }, {0.9, 0.5, 0.0});
  add("clump1000", kClumpSeconds, [] { return clump(1000); }, {0.9, 0.5, 0.0});
  add("clump10000", kClumpSeconds, [] { return clump(10000); }, {0.9, 0.0});
  // Fig. 6.7 as the impulse chapter reads it: thrown towards the ground's centre, it piles up
  // and settles by about 13 s (its own restitution, 0.5).
  add("clump100_ground", 15.0, [] { return fromFile("clump100_ground"); }, {0.5});
  return scenes;
}

/// The scenes asked for: `bases` (all when empty, unless `files` names scenes of the user's),
/// then `files` (sceneFromFile, `fileSeconds` long), with the restitution and sleeping the
/// command line imposes on every one; variants made equal by them are run once.
std::vector<SceneSpec> chosenScenes(const std::vector<std::string>& bases,
                                    std::optional<double> restitution, std::optional<bool> sleep,
                                    double friction, double durationScale,
                                    unsigned long perturbSeed = 0,
                                    const std::vector<std::string>& files = {},
                                    double fileSeconds = 5.0) {
  std::vector<SceneSpec> all = comparisonScenes();
  if (!files.empty() && bases.empty()) all.clear();
  for (const std::string& file : files) all.push_back(sceneFromFile(file, fileSeconds));
  for (const std::string& base : bases)
    if (std::none_of(all.begin(), all.end(), [&](const SceneSpec& s) { return s.base == base; })) {
      std::string known;
      for (const SceneSpec& s : all)
        if (known.find(s.base + ",") == std::string::npos) known += s.base + ", ";
      throw std::invalid_argument("unknown scene '" + base + "'; known scenes: " +
                                  known.substr(0, known.size() - 2));
    }
  std::vector<SceneSpec> chosen;
  for (std::size_t k = 0; k < all.size(); ++k) {
    SceneSpec spec = all[k];
    // The files' scenes come last and are always run; the page's own as `bases` choose.
    const bool fromFile = k + files.size() >= all.size();
    if (!fromFile && !bases.empty() && std::find(bases.begin(), bases.end(), spec.base) == bases.end())
      continue;
    if (restitution) spec.restitution = *restitution;
    if (sleep) spec.sleep = *sleep;
    spec.friction = friction;
    spec.duration *= durationScale;
    if (perturbSeed != 0)
      spec.build = [build = spec.build, perturbSeed] { return perturbed(build(), perturbSeed); };
    if (std::none_of(chosen.begin(), chosen.end(), [&](const SceneSpec& s) { return s.label() == spec.label(); }))
      chosen.push_back(spec);
  }
  return chosen;
}

std::unique_ptr<PeerEngine> makeEngine(const std::string& name) {
#ifdef BOXSIM_HAVE_BULLET
  if (name == "bullet" || name == "bullet/ccd") return makeBulletEngine(name == "bullet/ccd");
#endif
#ifdef BOXSIM_HAVE_ODE
  if (name == "ode") return makeOdeEngine();
#endif
  if (name.rfind("bullet", 0) == 0 || name == "ode")
    throw std::invalid_argument("engine '" + name + "' was not found at configure time; install lib" +
                                (name == "ode" ? std::string("ode") : std::string("bullet")) +
                                "-dev and configure again");
  return makeBoxsimEngine(name);
}

/// The peers found at configure time for one scene: Bullet, with its CCD too where a box is
/// launched, and ODE.
std::vector<std::string> peersOf(const SceneSpec& spec) {
  std::vector<std::string> peers;
#ifdef BOXSIM_HAVE_BULLET
  peers.push_back("bullet");
  if (spec.launches) peers.push_back("bullet/ccd");
#endif
#ifdef BOXSIM_HAVE_ODE
  peers.push_back("ode");
#endif
  (void)spec;
  return peers;
}

/// Whether `spec` is one of the dense scenes, where boxsim damped runs on two threads too and
/// its shared work is measured for the model of more cores.
bool denseScene(const SceneSpec& spec) {
  return !spec.userFile &&
         (spec.base == "pile343" || spec.base == "clump1000" || spec.base == "clump10000");
}

/// The engines of one scene: those asked for, or by default boxsim damped integration
/// (frictionless as the thesis, and with the peers' friction; with chatter detection, stability
/// under load and impact passes; frictionless with impact passes and damping of supported
/// bodies only) and every peer found (peersOf).
std::vector<std::string> enginesOf(const SceneSpec& spec, const std::vector<std::string>& asked) {
  if (!asked.empty()) return asked;
  std::vector<std::string> engines = {"damped", "damped+friction", "damped+chatter",
                                      "damped+under_load", "damped+impact",
                                      "damped+friction+impact", "damped+supported+impact"};
  // The dense scenes, on two threads too (issue of threads: the model on the page).
  if (denseScene(spec)) {
    engines.push_back("damped+threads2");
    engines.push_back("damped+friction+threads2");
  }
  for (const std::string& peer : peersOf(spec)) engines.push_back(peer);
  return engines;
}

/// Runs every engine on `spec`, `reps` times, interleaved.
SceneResults runScene(const SceneSpec& spec, const std::vector<std::string>& engines, RunSetup& setup) {
  SceneResults results{spec, std::vector<RunResult>(engines.size())};
  for (int rep = 0; rep < setup.reps; ++rep)
    for (std::size_t i = 0; i < engines.size(); ++i) {
      std::unique_ptr<PeerEngine> engine = makeEngine(engines[i]);
      setup.settings[engine->name()] = engine->settings();
      runRepetition(spec, *engine, setup.dt, results.runs[i]);
    }
  // What boxsim damped's threads would share, in an untimed run of its own on one thread, and
  // what the same loops took in one on two threads.
  if (denseScene(spec))
    for (std::size_t i = 0; i < engines.size(); ++i)
      if (engines[i] == "damped" || engines[i] == "damped+friction") {
        const auto measured = [&](const std::string& suffix) {
          std::unique_ptr<PeerEngine> engine = makeEngine(engines[i] + suffix + "+shared_work");
          runOnce(spec, engine.get(), setup.dt);
          return engine->sharedWork();
        };
        results.runs[i].sharedWork = measured("");
        results.runs[i].sharedWorkTwoThreads = measured("+threads2");
      }
  // The largest clump's memory: each engine in a fresh process of its own, and the same
  // process stepping nothing for the part that is the scene and the program.
  if (!spec.userFile && spec.base == "clump10000") {
    const auto memoryRun = [&](const std::string& engine) {
      return peakResidentOfRun({"--memory-run", engine, "--scene", spec.base,
                              "--restitution", shortestText(spec.restitution), "--sleep",
                              spec.sleep ? "on" : "off", "--friction", shortestText(spec.friction),
                              "--memory-seconds", shortestText(spec.duration)});
    };
    const long idle = memoryRun("none");
    for (std::size_t i = 0; i < engines.size(); ++i) {
      results.runs[i].peakRssKiB = memoryRun(engines[i]);
      results.runs[i].startRssKiB = idle;
    }
  }
  const RunResult* boxsim = nullptr;
  for (const RunResult& r : results.runs)
    if (r.engine == "boxsim damped") boxsim = &r;
  for (const RunResult& r : results.runs)
    std::fprintf(stderr, "%-28s %-16s mean %9.4f ms  median %9.4f  p95 %9.4f%s\n",
                 spec.label().c_str(), r.engine.c_str(), r.meanMs(), r.medianMs(), r.p95Ms(),
                 boxsim && boxsim != &r
                     ? ("  mean / boxsim damped mean " + std::to_string(r.meanMs() / boxsim->meanMs())).c_str()
                     : "");
  return results;
}

std::string absentPeers() {
  std::string absent;
#ifndef BOXSIM_HAVE_BULLET
  absent += "Bullet (libbullet-dev) ";
#endif
#ifndef BOXSIM_HAVE_ODE
  absent += "ODE (libode-dev) ";
#endif
  return absent;
}

/// The native section's markers in the page: bench_peers keeps what lies between them.
constexpr const char* kNativeBegin = "<!-- native build: written by bench_native -->";
constexpr const char* kNativeEnd = "<!-- end of native build -->";

/// The native section of `page` with its markers, or "" when it has none.
std::string nativeSectionOf(const std::string& page) {
  const std::size_t begin = page.find(kNativeBegin), end = page.find(kNativeEnd);
  if (begin == std::string::npos || end == std::string::npos || end < begin) return "";
  return page.substr(begin, end + std::string(kNativeEnd).size() - begin) + "\n";
}

/// `page` with its native section replaced by `section` (appended where it has none).
std::string withNativeSection(const std::string& page, const std::string& section) {
  const std::string old = nativeSectionOf(page);
  if (old.empty()) return section.empty() ? page : page + "\n" + section;
  std::string out = page;
  out.replace(out.find(old), old.size(), section);
  return out;
}

/// The text of the file at `path`, or "" where there is none.
std::string fileText(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// One timed repetition of boxsim damped integration on `spec`: mean ms per step and the
/// digest of the final poses.
std::pair<double, std::uint64_t> timedDampedRun(const SceneSpec& spec, double dt) {
  std::unique_ptr<PeerEngine> engine = makeEngine("damped");
  RunResult result;
  runRepetition(spec, *engine, dt, result);
  std::vector<PeerPose> poses;
  engine->read(poses);
  return {result.meanMs(), poseDigest(poses)};
}

/// The native section: boxsim damped integration built as the project builds it against the
/// same sources built with -march=native (`native`, that build's boxsim_peers), each scene's
/// repetitions in turn, this process then a fresh native one.
std::string nativeSection(const std::vector<SceneSpec>& scenes, const std::string& native,
                          double durationScale, const RunSetup& setup,
                          const std::string& stampText, const std::string& command) {
  std::ostringstream rows;
  for (const SceneSpec& spec : scenes) {
    std::vector<double> portable, tuned;
    std::uint64_t portableDigest = 0, nativeDigest = 0;
    for (int rep = 0; rep < setup.reps; ++rep) {
      const auto [ms, digest] = timedDampedRun(spec, setup.dt);
      portable.push_back(ms);
      portableDigest = digest;
      const std::optional<std::string> output =
          outputOfRun(native, {"--timing-run", "damped", "--scene", spec.base, "--restitution",
                               shortestText(spec.restitution), "--sleep", spec.sleep ? "on" : "off",
                               "--friction", shortestText(spec.friction), "--duration-scale",
                               shortestText(durationScale)});
      double nativeMs = 0.0;
      unsigned long long nativeBits = 0;
      if (!output || std::sscanf(output->c_str(), "%lf %llx", &nativeMs, &nativeBits) != 2)
        throw std::runtime_error("the native build (" + native + ") did not run " + spec.label());
      tuned.push_back(nativeMs);
      nativeDigest = nativeBits;
    }
    const auto mean = [](const std::vector<double>& v) {
      return std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
    };
    const auto range = [](const std::vector<double>& v) {
      const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
      return shortestText(std::round(*lo * 1000.0) / 1000.0) + "–" +
             shortestText(std::round(*hi * 1000.0) / 1000.0);
    };
    char ratio[32];
    std::snprintf(ratio, sizeof ratio, "%.2f", mean(tuned) / mean(portable));
    rows << "| " << spec.label() << " | " << range(portable) << " | " << range(tuned) << " | "
         << ratio << " | " << (portableDigest == nativeDigest ? "yes" : "**no**") << " |\n";
    std::fprintf(stderr, "%-28s portable %.4f ms  native %.4f ms  native / portable %s\n",
                 spec.label().c_str(), mean(portable), mean(tuned), ratio);
  }
  std::ostringstream out;
  out << kNativeBegin << "\n## What -march=native would add\n\n"
      << "Written by `boxsim_peers --native` (`cmake --build build --target bench_native`); do "
         "not edit by hand.\n\n"
      << stampText << "- command: `" << command << "`\n\n"
      << "boxsim damped integration as the project builds it (portable: no -march) against the same "
         "sources built with `-march=native` for this machine, each repetition in turn: this "
         "process, then a fresh process of the native build. *Rep means* are the repetitions' "
         "mean ms per step; the ratio is the native build's mean over the portable one's (below "
         "1: native is faster). *Same bits* compares the final poses of the two builds bit for bit: "
         "GCC may fuse a multiply and an add into one FMA instruction where the target has one, "
         "which rounds once instead of twice.\n\n"
      << "| scene | portable rep means (ms) | native rep means (ms) | native ÷ portable | same bits |\n"
      << "|---|---|---|---|---|\n"
      << rows.str() << "\n"
      << kNativeEnd << "\n";
  return out.str();
}

/// The impact page (peer_impact.hpp): the scenes asked for, which must launch a box, or by
/// default every scene of the comparison that does (the shot pyramids), each at its own
/// restitution and at 0 unless `restitution` fixes one, under the engines asked for or by
/// default boxsim's damped integration and plain impulse step with the peers' friction and
/// every peer found.
std::string impactRun(const std::vector<std::string>& bases, std::optional<double> restitution,
                      std::optional<bool> sleep, double friction,
                      const std::vector<std::string>& engines, double dt,
                      const std::string& stampText, const std::string& command) {
  std::vector<ImpactRow> rows;
  for (const SceneSpec& own : chosenScenes(bases, restitution, sleep, friction, 1.0)) {
    if (!own.launches) {
      if (bases.empty()) continue;
      throw std::invalid_argument("--impact: scene '" + own.base +
                                  "' launches no box; use a shot scene");
    }
    std::vector<SceneSpec> specs = {own};
    if (!restitution && own.restitution != 0.0) {
      SceneSpec still = own;
      still.restitution = 0.0;
      specs.push_back(still);
    }
    for (const SceneSpec& spec : specs) {
      std::vector<std::string> names = engines;
      if (names.empty()) {
        names = {"damped+friction", "impulse+friction"};
        for (const std::string& peer : peersOf(spec)) names.push_back(peer);
      }
      for (const std::string& name : names) {
        std::unique_ptr<PeerEngine> engine = makeEngine(name);
        rows.push_back({spec.label(), engine->name(), measureImpact(spec, *engine, dt)});
      }
    }
  }
  return impactPage(rows, friction, stampText, command);
}

std::string commandLine(int argc, char** argv) {
  std::string text = "boxsim_peers";
  for (int i = 1; i < argc; ++i) text += std::string(" ") + argv[i];
  return text;
}

}  // namespace
}  // namespace boxsim::peers

int main(int argc, char** argv) {
  using namespace boxsim::peers;
  CLI::App app("boxsim side by side with Bullet and ODE on the thesis' scenes");
  std::vector<std::string> sceneNames, engineNames;
  std::string tablePath, scalingPath, sleepText;
  std::optional<double> restitution;
  double friction = 0.5, durationScale = 1.0;
  RunSetup setup;
  app.add_option("--scene", sceneNames, "Scene to run (repeatable; default: all, or none when --scene-file is given)");
  std::vector<std::string> sceneFiles;
  double fileSeconds = 5.0;
  app.add_option("--scene-file", sceneFiles,
                 "A scene file of your own (docs/scene_format.md; repeatable), run under every engine "
                 "as the page's scenes are, at its own restitution; its bodies' friction is left out "
                 "(boxsim's '+friction' engines and the peers take --friction)")
      ->check(CLI::ExistingFile);
  app.add_option("--duration", fileSeconds, "Simulated time of every --scene-file scene, s")
      ->check(CLI::Range(1e-3, 1e4));
  app.add_option("--engine", engineNames,
                 "Engine (repeatable): a boxsim method (damped, impulse, ...), optionally with a "
                 "contact gathering after a slash (damped/every_pass), and '+friction' for the "
                 "peers' Coulomb friction (damped+friction), '+chatter' for chatter detected from "
                 "history (damped+chatter), '+under_load' for stability under load "
                 "(damped+under_load), '+impact' for 20 impact passes (damped+impact), "
                 "'+supported' for damping of supported bodies only (damped+supported), "
                 "'+anchor' for the predicted anchor (damped+anchor), '+exact_edges' for "
                 "edge-edge pairs gathered exactly (damped+exact_edges), '+corners' for an "
                 "edge-edge pair's face corners kept beside its point (damped+corners); bullet, "
                 "bullet/ccd, ode (default: damped, damped+friction, damped+chatter, "
                 "damped+under_load, damped+impact, damped+friction+impact, "
                 "damped+supported+impact and every peer found, Bullet's CCD too on the shot "
                 "pyramids)");
  app.add_option("--restitution", restitution, "Restitution of every scene (default: each scene's own)")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--sleep", sleepText, "Sleeping of every engine, on or off (default: each scene's own)")
      ->check(CLI::IsMember({"on", "off"}));
  app.add_option("--friction", friction, "Coulomb friction of the peers' contacts and of boxsim's '+friction' engines")
      ->check(CLI::Range(0.0, 10.0));
  app.add_option("--reps", setup.reps, "Repetitions of every scene and engine, interleaved")
      ->check(CLI::Range(1, 100));
  app.add_option("--table", tablePath, "Write the Markdown page here (docs/benchmarks.md)");
  app.add_option("--scaling", scalingPath, "Write the scaling figure's data (the clumps at e = 0) here");
  app.add_option("--duration-scale", durationScale, "Multiply every scene's duration (0.1 for a quick look)")
      ->check(CLI::Range(1e-3, 100.0));
  std::string baselinePath;
  app.add_option("--baseline", baselinePath,
                 "A page this tool wrote before (docs/benchmarks.md of an earlier commit): the "
                 "new page compares every boxsim row's physics with it, before and after")
      ->check(CLI::ExistingFile);
  unsigned long perturbSeed = 0;
  app.add_option("--perturb", perturbSeed,
                 "Nudge every movable body's starting velocity by a random 1 µm/s at most (each "
                 "component), seeded by this (default 0: no nudge), for the spread of a chaotic "
                 "scene's measures: run seeds 1, 2, 3, ...")
      ->check(CLI::Range(0, 1000000));
  // A memory run (the comparison starts these itself): the one scene, once, under one engine
  // ("none": the scene built, nothing stepped), untimed, for the peak resident set.
  std::string memoryEngine;
  double memorySeconds = 0.0;
  app.add_option("--memory-run", memoryEngine)->group("");
  app.add_option("--memory-seconds", memorySeconds)->group("");
  // A timing run (the native comparison starts these in its other build): the one scene, once,
  // under one engine; prints its mean ms per step and the digest of its final poses.
  std::string timingEngine;
  app.add_option("--timing-run", timingEngine)->group("");
  std::string impactPath;
  app.add_option("--impact", impactPath,
                 "Measure the shot pyramids' impact under every engine with the same friction "
                 "(at the scene's restitution and at 0) and write that page here "
                 "(docs/shot_impact.md); times nothing");
  std::string nativePath;
  app.add_option("--native", nativePath,
                 "Compare boxsim damped with the boxsim_peers of a -march=native build at this path "
                 "(bench_native) and write that section of the page alone");
  CLI11_PARSE(app, argc, argv);
  std::optional<bool> sleep;
  if (!sleepText.empty()) sleep = sleepText == "on";
  if (!memoryEngine.empty()) {
    try {
      std::vector<SceneSpec> specs = chosenScenes(sceneNames, restitution, sleep, friction, 1.0);
      if (specs.size() != 1) throw std::invalid_argument("a memory run takes exactly one scene");
      specs.front().duration = memorySeconds;
      std::unique_ptr<PeerEngine> engine;
      if (memoryEngine != "none") engine = makeEngine(memoryEngine);
      runOnce(specs.front(), engine.get(), setup.dt);
      std::cout << peakResidentKiB() << "\n";
    } catch (const std::exception& e) {
      std::cerr << "boxsim_peers: error: " << e.what() << "\n";
      return 2;
    }
    return 0;
  }

  if (!timingEngine.empty()) {
    try {
      const std::vector<SceneSpec> specs =
          chosenScenes(sceneNames, restitution, sleep, friction, durationScale);
      if (specs.size() != 1) throw std::invalid_argument("a timing run takes exactly one scene");
      std::unique_ptr<PeerEngine> engine = makeEngine(timingEngine);
      RunResult result;
      runRepetition(specs.front(), *engine, setup.dt, result);
      std::vector<PeerPose> poses;
      engine->read(poses);
      std::printf("%.17g %llx\n", result.meanMs(),
                  static_cast<unsigned long long>(poseDigest(poses)));
    } catch (const std::exception& e) {
      std::cerr << "boxsim_peers: error: " << e.what() << "\n";
      return 2;
    }
    return 0;
  }

  try {
    setup.command = commandLine(argc, argv);
    if (!nativePath.empty() && (perturbSeed != 0 || !baselinePath.empty()))
      throw std::invalid_argument(
          "--native measures the scenes as they are and writes its section alone: run it "
          "without --perturb and --baseline");
    if (!impactPath.empty()) {
      const std::string page = impactRun(sceneNames, restitution, sleep, friction, engineNames,
                                         setup.dt, stamp(BOXSIM_SOURCE_DIR), setup.command);
      std::cout << page;
      boxsim::writeFileAtomically(impactPath, page);
      return 0;
    }
    if (!nativePath.empty()) {
      const std::string stampText = stamp(BOXSIM_SOURCE_DIR);
      const std::string section =
          nativeSection(chosenScenes(sceneNames, restitution, sleep, friction, durationScale),
                        nativePath, durationScale, setup, stampText, setup.command);
      std::cout << section;
      if (!tablePath.empty())
        boxsim::writeFileAtomically(tablePath, withNativeSection(fileText(tablePath), section));
      return 0;
    }
    setup.absent = absentPeers();
    // Read before the comparison runs: a page with no table fails now, not after it.
    if (!baselinePath.empty()) setup.baseline = parseBaseline(fileText(baselinePath), baselinePath);
    // Stamped as the timing begins: the tree the binary was just built from (the bench_peers
    // target builds it first); edits made while the comparison runs are not in its numbers.
    const std::string stampText = stamp(BOXSIM_SOURCE_DIR);
    std::vector<SceneResults> results;
    for (const SceneSpec& spec : chosenScenes(sceneNames, restitution, sleep, friction,
                                              durationScale, perturbSeed, sceneFiles, fileSeconds))
      results.push_back(runScene(spec, enginesOf(spec, engineNames), setup));
    // The native section, measured by its own target, stays as it was.
    const std::string page = withNativeSection(markdownPage(results, setup, stampText),
                                               tablePath.empty() ? "" : nativeSectionOf(fileText(tablePath)));
    std::cout << page;
    if (!tablePath.empty()) boxsim::writeFileAtomically(tablePath, page);
    if (!scalingPath.empty())
      boxsim::writeFileAtomically(scalingPath, scalingData(results, 0.0, setup, stampText));
  } catch (const std::exception& e) {
    std::cerr << "boxsim_peers: error: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
