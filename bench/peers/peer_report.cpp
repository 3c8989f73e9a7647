#include "peer_report.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <vector>

namespace boxsim::peers {

namespace {

constexpr const char* kBoxsim = "boxsim damped";
/// The boxsim rows the summary and the aims speak of: the thesis' frictionless damped
/// integration, the same with the peers' Coulomb friction (the like-for-like row), with
/// chatter detected from history and with stability under load (both §6.3.1), both of the
/// first with impact passes, and the first with impact passes and damping of supported bodies
/// only (deviations, off by default).
constexpr const char* kBoxsimRows[] = {"boxsim damped",          "boxsim damped μ",
                                       "boxsim damped chatter",  "boxsim damped under load",
                                       "boxsim damped impact",   "boxsim damped μ impact",
                                       "boxsim damped supported impact"};

std::string fixed(double value, int digits) {
  if (std::isnan(value)) return "–";
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", digits, value);
  return text;
}

/// Milliseconds with three significant digits at least, so 0.0012 and 140 both read well.
std::string ms(double value) {
  const int digits = value >= 100 ? 0 : value >= 10 ? 1 : value >= 1 ? 2 : value >= 0.01 ? 3 : 4;
  return fixed(value, digits);
}

std::string seconds(double value) { return value < 0 ? "never" : fixed(value, 2); }

/// A row's measures as the page prints them (tableRow, baselineComparison).
PrintedPhysics printed(const RunMeasures& m) {
  return PrintedPhysics{fixed(1000 * m.meanPenetration, 1), fixed(1000 * m.finalPenetration, 1),
                        fixed(m.finalKinetic, 3), seconds(m.allAsleepFrom)};
}

/// The first line a shell command prints, without its newline; empty when it fails.
std::string firstLineOf(const std::string& command) {
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  if (!pipe) return "";
  std::array<char, 256> line{};
  if (!std::fgets(line.data(), static_cast<int>(line.size()), pipe.get())) return "";
  std::string text = line.data();
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  return text;
}

/// The value of the first line of a /proc file that starts with `key`, e.g. "model name".
std::string procField(const std::string& path, const std::string& key) {
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);)
    if (line.rfind(key, 0) == 0) {
      const std::size_t colon = line.find(':');
      std::string value = colon == std::string::npos ? line : line.substr(colon + 1);
      value.erase(0, value.find_first_not_of(" \t"));
      return value;
    }
  return "unknown";
}

const RunResult* find(const SceneResults& scene, const std::string& engine) {
  for (const RunResult& r : scene.runs)
    if (r.engine == engine) return &r;
  return nullptr;
}

/// The peer (not boxsim) with the lowest mean ms per step, or nullptr.
const RunResult* fasterPeer(const SceneResults& scene) {
  const RunResult* best = nullptr;
  for (const RunResult& r : scene.runs)
    if (r.engine.rfind("boxsim", 0) != 0 && (!best || r.meanMs() < best->meanMs())) best = &r;
  return best;
}

/// "die 10 s, tower10 10 s, ...": each base scene's simulated time, once.
std::string durations(const std::vector<SceneResults>& scenes) {
  std::string text;
  for (const SceneResults& s : scenes) {
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%g", s.spec.duration);
    const std::string item = s.spec.base + " " + seconds + " s";
    if (text.find(s.spec.base + " ") == std::string::npos) text += (text.empty() ? "" : ", ") + item;
  }
  return text;
}

/// The first engine whose name starts with `prefix`, Bullet's CCD row aside, or nullptr.
const RunResult* engineStarting(const SceneResults& scene, const std::string& prefix) {
  for (const RunResult& r : scene.runs)
    if (r.engine.rfind(prefix, 0) == 0 && r.engine.find("CCD") == std::string::npos) return &r;
  return nullptr;
}

/// m: the shallowest final penetration of the peers (not boxsim) in the scene; infinity: none.
double bestPeerFinalPenetration(const SceneResults& scene) {
  double best = INFINITY;
  for (const RunResult& r : scene.runs)
    if (r.engine.rfind("boxsim", 0) != 0) best = std::min(best, r.measures.finalPenetration);
  return best;
}

std::string tableRow(const SceneResults& scene, const RunResult& r) {
  const RunMeasures& m = r.measures;
  const PrintedPhysics shown = printed(m);
  const RunResult* boxsim = find(scene, kBoxsim);
  const auto [lo, hi] = std::minmax_element(r.repMeanMs.begin(), r.repMeanMs.end());
  std::ostringstream out;
  out << "| " << scene.spec.label() << " | " << m.bodies << " | " << r.engine << " | **"
      << ms(r.meanMs()) << "** | " << ms(r.medianMs()) << " | " << ms(r.p95Ms()) << " | "
      << ms(*lo) << "–" << ms(*hi) << " | "
      << (boxsim && boxsim != &r ? fixed(r.meanMs() / boxsim->meanMs(), 2) : "") << " | "
      << shown.meanPenetration << " / " << shown.finalPenetration << " / "
      << fixed(1000 * m.maxPenetration, 1) << " | " << shown.kinetic << " | "
      << m.asleepAtEnd << " | " << shown.allAsleep << " | " << seconds(m.allAtRestFrom)
      << " | " << (m.drift < 0 ? "–" : fixed(1000 * m.drift, 1)) << " | "
      << (r.work ? fixed(r.work->narrowPhasesPerTouchingPair, 2) + " (" +
                       fixed(r.work->passNarrowPhasesPerTouchingPair, 2) + "; " +
                       fixed(r.work->keptPerTouchingPair, 2) + ") + " +
                       fixed(r.work->axisChecksPerTouchingPair, 2) + " · " +
                       fixed(r.work->passesPerStep, 1)
                 : "–")
      << " |\n";
  return out.str();
}

/// Where one boxsim row (`engine`) is ahead of and behind the faster peer, in plain lists;
/// empty when no scene has that row.
std::string summaryOf(const std::vector<SceneResults>& scenes, const std::string& engine) {
  std::ostringstream ahead, behind, deeper, later;
  bool present = false;
  for (const SceneResults& s : scenes) {
    const RunResult* boxsim = find(s, engine);
    const RunResult* peer = fasterPeer(s);
    if (!boxsim || !peer) continue;
    present = true;
    const double ratio = boxsim->meanMs() / peer->meanMs();
    (ratio < 1 ? ahead : behind) << "- " << s.spec.label() << ": " << fixed(ratio, 2) << "× "
                                 << peer->engine << "'s mean\n";
    const double bestFinal = bestPeerFinalPenetration(s);
    if (boxsim->measures.finalPenetration > bestFinal + 1e-4)
      deeper << "- " << s.spec.label() << ": " << fixed(1000 * boxsim->measures.finalPenetration, 1)
             << " mm against " << fixed(1000 * bestFinal, 1) << " mm\n";
    const RunResult* bullet = engineStarting(s, "Bullet");
    if (bullet && s.spec.sleep && bullet->measures.allAsleepFrom >= 0 &&
        (boxsim->measures.allAsleepFrom < 0 ||
         boxsim->measures.allAsleepFrom > bullet->measures.allAsleepFrom))
      later << "- " << s.spec.label() << ": " << seconds(boxsim->measures.allAsleepFrom)
            << " against Bullet's " << seconds(bullet->measures.allAsleepFrom) << " s\n";
  }
  if (!present) return "";
  auto section = [](const std::string& title, const std::string& body) {
    return "**" + title + "**\n\n" + (body.empty() ? "- none\n" : body) + "\n";
  };
  return section(engine + " is faster than the faster peer (its mean ms/step as a multiple of that peer's):", ahead.str()) +
         section(engine + " is slower than the faster peer:", behind.str()) +
         section(engine + " ends deeper in penetration than the best peer:", deeper.str()) +
         section(engine + " has every box asleep later than Bullet, or never:", later.str());
}

/// The summary of every boxsim row (kBoxsimRows) present.
std::string summary(const std::vector<SceneResults>& scenes) {
  std::string text;
  for (const char* engine : kBoxsimRows) text += summaryOf(scenes, engine);
  return text;
}

const SceneResults* sceneOf(const std::vector<SceneResults>& scenes, const std::string& base,
                            double restitution) {
  for (const SceneResults& s : scenes)
    if (!s.spec.userFile && s.spec.base == base && s.spec.restitution == restitution && s.spec.sleep) return &s;
  return nullptr;
}

/// The dense-pile aims: boxsim damped at most half the faster peer's mean, no deeper final
/// penetration than the best peer, every box asleep no later than Bullet; on the 10 000-cube
/// clump, faster than ODE. Each line says met or missed, with the measured numbers.
std::string aims(const std::vector<SceneResults>& scenes) {
  std::ostringstream out;
  const auto verdict = [](bool met) { return met ? "met" : "**missed**"; };
  const std::pair<const char*, double> piles[] = {{"clump1000", 0.0}, {"pile343", 0.0}, {"pile343", 0.9}};
  for (const char* engine : kBoxsimRows)
  for (const auto& [base, e] : piles) {
    const SceneResults* s = sceneOf(scenes, base, e);
    const RunResult* boxsim = s ? find(*s, engine) : nullptr;
    const RunResult* peer = s ? fasterPeer(*s) : nullptr;
    if (!boxsim || !peer) continue;
    const double ratio = boxsim->meanMs() / peer->meanMs();
    const double bestFinal = bestPeerFinalPenetration(*s);
    const RunResult* bullet = engineStarting(*s, "Bullet");
    const double mine = boxsim->measures.allAsleepFrom;
    const double theirs = bullet ? bullet->measures.allAsleepFrom : -1;
    out << "- " << engine << ", " << s->spec.label() << ": speed " << verdict(ratio <= 0.5) << " (" << fixed(ratio, 2)
        << "× " << peer->engine << "'s mean, aim ≤ 0.5); final penetration "
        << verdict(boxsim->measures.finalPenetration <= bestFinal) << " ("
        << fixed(1000 * boxsim->measures.finalPenetration, 1) << " mm, best peer "
        << fixed(1000 * bestFinal, 1) << " mm); all asleep "
        << verdict(mine >= 0 && (theirs < 0 || mine <= theirs)) << " (" << seconds(mine)
        << ", Bullet " << seconds(theirs) << ")\n";
  }
  for (const char* engine : kBoxsimRows)
  for (double e : {0.9, 0.0}) {
    const SceneResults* s = sceneOf(scenes, "clump10000", e);
    const RunResult* boxsim = s ? find(*s, engine) : nullptr;
    const RunResult* ode = s ? engineStarting(*s, "ODE") : nullptr;
    if (!boxsim || !ode) continue;
    out << "- " << engine << ", " << s->spec.label() << ": faster than ODE " << verdict(boxsim->meanMs() < ode->meanMs())
        << " (" << ms(boxsim->meanMs()) << " against " << ms(ode->meanMs()) << " ms); "
        << fixed(boxsim->meanMs() / (1000.0 / 60.0), 1) << "× the 16.7 ms of 60 Hz\n";
  }
  return out.str().empty() ? "" : "**Dense-pile aims** (the project's targets for damped integration on piles):\n\n" + out.str() + "\n";
}

/// Where boxsim's step goes on the scenes of the dense-pile aims: the first repetition's step
/// time by stage (RunResult::stages), largest first.
std::string stages(const std::vector<SceneResults>& scenes) {
  std::ostringstream out;
  const std::pair<const char*, double> dense[] = {{"pile343", 0.0},    {"pile343", 0.9},
                                                  {"clump1000", 0.0},  {"clump10000", 0.9},
                                                  {"clump10000", 0.0}};
  for (const char* engine : kBoxsimRows)
    for (const auto& [base, e] : dense) {
      const SceneResults* s = sceneOf(scenes, base, e);
      const RunResult* r = s ? find(*s, engine) : nullptr;
      if (!r || r->stages.empty() || !(r->stagedStepsMs > 0.0)) continue;
      const std::size_t steps = r->stepMs.size() / std::max<std::size_t>(1, r->repMeanMs.size());
      out << "- " << engine << ", " << s->spec.label() << " ("
          << ms(r->stagedStepsMs / static_cast<double>(std::max<std::size_t>(1, steps)))
          << " ms a step): ";
      double staged = 0.0;
      for (std::size_t k = 0; k < r->stages.size(); ++k) {
        staged += 1000.0 * r->stages[k].second;
        out << (k ? ", " : "") << r->stages[k].first << " "
            << fixed(100.0 * 1000.0 * r->stages[k].second / r->stagedStepsMs, 0) << " %";
      }
      out << "; outside them " << fixed(100.0 * (1.0 - staged / r->stagedStepsMs), 0) << " %\n";
    }
  if (out.str().empty()) return "";
  return "**Where the step goes** (boxsim on the scenes of the aims: the first repetition's step "
         "time by stage of A.2, each stage with the contact gathering and narrow phases it runs; "
         "[the impulse chapter](../chapters/impulse_damped/README.md) says what each costs and "
         "why):\n\n" + out.str() + "\n";
}

/// What more cores would buy boxsim damped on the dense scenes: the shared work of an untimed
/// one-thread run (RunResult::sharedWork) in Amdahl's law with each loop's rounds
/// (ParallelWork), beside the two-thread rows measured here.
std::string coresModel(const std::vector<SceneResults>& scenes) {
  std::ostringstream out;
  const std::pair<const char*, double> dense[] = {
      {"pile343", 0.0},   {"pile343", 0.9},    {"clump1000", 0.0}, {"clump1000", 0.5},
      {"clump1000", 0.9}, {"clump10000", 0.0}, {"clump10000", 0.9}};
  for (const char* engine : {"boxsim damped", "boxsim damped μ"})
    for (const auto& [base, e] : dense) {
      const SceneResults* s = sceneOf(scenes, base, e);
      const RunResult* r = s ? find(*s, engine) : nullptr;
      if (!r || !r->sharedWork || !(r->sharedWork->stepSeconds > 0.0)) continue;
      const SharedWork& w = *r->sharedWork;
      const double tests = w.work.testSeconds / w.stepSeconds;
      const double levels = w.work.levelSeconds / w.stepSeconds;
      const double kept = w.work.keptSeconds / w.stepSeconds;
      const double shared = tests + levels + kept;
      // Time on N threads over time on one: the serial rest, and each shared kind in the rounds
      // N threads take.
      const auto speedup = [&](std::size_t i) {
        const auto part = [&](double share, const ParallelWork::Rounds& rounds) {
          return rounds[0] > 0 ? share * static_cast<double>(rounds[i]) /
                                     static_cast<double>(rounds[0])
                               : share;
        };
        return 1.0 / ((1.0 - shared) + part(tests, w.work.testRounds) +
                      part(levels, w.work.levelRounds) + part(kept, w.work.keptRounds));
      };
      out << "- " << engine << ", " << s->spec.label() << ": shared "
          << fixed(100.0 * shared, 0) << " % (the fast pairs' narrow phases "
          << fixed(100.0 * tests, 0) << " %, COLLIDE's levels " << fixed(100.0 * levels, 0)
          << " %, the kept narrow phases of the step's start and FIXCONTACTCONSTRAINTS "
          << fixed(100.0 * kept, 0) << " %); the model";
      for (std::size_t i = 1; i < ParallelWork::threadCounts.size(); ++i)
        out << (i > 1 ? "," : "") << " " << ParallelWork::threadCounts[i] << " threads "
            << fixed(speedup(i), 2) << "×";
      out << " (Amdahl's bound " << fixed(1.0 / (1.0 - shared), 2) << "×)";
      const RunResult* two = find(*s, std::string(engine) + " 2 threads");
      if (two && two->meanMs() > 0.0)
        out << "; measured here on 2 threads " << fixed(r->meanMs() / two->meanMs(), 2)
            << "× (the means of the two rows)";
      const SharedWork* t = r->sharedWorkTwoThreads ? &*r->sharedWorkTwoThreads : nullptr;
      if (t && t->steps > 0 && w.steps > 0 && shared > 0.0) {
        // The same loops and the rest of the step, in ms a step, on one thread and on two.
        const auto loops = [](const SharedWork& x) {
          return x.work.testSeconds + x.work.levelSeconds + x.work.keptSeconds;
        };
        const auto ms = [](double seconds, long steps) {
          return fixed(1000.0 * seconds / static_cast<double>(steps), 2);
        };
        // The model's loops on 2 threads, as a share of the one-thread step.
        const double modelLoops = 1.0 / speedup(1) - (1.0 - shared);
        out << "; in untimed runs of their own the shared loops took " << ms(loops(w), w.steps)
            << " ms a step on 1 thread and " << ms(loops(*t), t->steps) << " on 2 ("
            << fixed(loops(w) / std::max(loops(*t), 1e-12), 2) << "×, the model "
            << fixed(shared / modelLoops, 2) << "×), the rest "
            << ms(w.stepSeconds - loops(w), w.steps) << " and "
            << ms(t->stepSeconds - loops(*t), t->steps) << " ms";
      }
      out << "\n";
    }
  if (out.str().empty()) return "";
  return "**What more cores would buy boxsim damped** (a model): the part of a step its threads "
         "share (ImpulseParams::threads; the impulse chapter, \"Threads\"), timed in an untimed "
         "run of its own on one thread, as a share of the step: the narrow phases of the pairs "
         "with a fast body in each pass, COLLIDE's loop in dependency levels, and the tests and "
         "clips of the kept narrow phases of the step's start and of FIXCONTACTCONSTRAINTS "
         "(KeptNarrowPhase::collideAll, two loops a batch). Everything else (the rest of the "
         "gathering and of the step's start, the passes' slow-pair prediction, "
         "FIXCONTACTCONSTRAINTS' nudges, damping, sleeping) runs on one thread. On N threads each "
         "shared loop of n items takes ceil(n / N) rounds, a level of COLLIDE being one loop; "
         "the model charges each kind its one-thread time "
         "times its rounds on N over its rounds on one, as if every item cost the same and the "
         "threads met for free, so it is an upper bound. The two-thread rows of the table are "
         "measured on this 2-core machine, where a second busy core slows the first (the impulse "
         "chapter, \"Threads\"); beside them, the shared loops and the rest of the step as they "
         "ran on 1 and on 2 threads, each in an untimed run of its own, show which part of the "
         "model this machine does not give (those runs read the clock around every loop, and "
         "plan each pass' pairs with a fast body before their narrow phases, as several threads "
         "do, so their steps on one thread are slower than the table's):\n\n" + out.str() + "\n";
}

/// \thesis{§6.1}: the frame rates the thesis reports (Fig. 6.6, the shot pyramid, 25 fps;
/// Fig. 6.7, the clump, 20 fps; both on a 1500 MHz AMD processor) beside boxsim damped's steps
/// here, one step a frame.
std::string realTime(const std::vector<SceneResults>& scenes) {
  struct Claim {
    const char* base;
    double restitution;
    const char* figure;
    double fps;
  };
  const Claim claims[] = {{"pyramid10_shot", 0.9, "Fig. 6.6", 25.0},
                          {"pyramid20_shot", 0.9, "Fig. 6.6", 25.0},
                          {"clump100_ground", 0.5, "Fig. 6.7", 20.0},
                          {"clump1000", 0.9, "Fig. 6.7 with 1000 cubes, 20 m up", 20.0}};
  std::ostringstream out;
  for (const Claim& claim : claims) {
    const SceneResults* s = sceneOf(scenes, claim.base, claim.restitution);
    const RunResult* r = s ? find(*s, "boxsim damped") : nullptr;
    if (!r || r->stepMs.empty()) continue;
    const double slowest = *std::max_element(r->stepMs.begin(), r->stepMs.end());
    out << "- " << claim.figure << ", " << s->spec.label() << " (" << s->spec.duration
        << " s): mean " << ms(r->meanMs()) << " ms a step, " << fixed(1000.0 / r->meanMs(), 0)
        << " steps a second; 95th percentile " << ms(r->p95Ms()) << " ms ("
        << fixed(1000.0 / r->p95Ms(), 0) << " a second); slowest step " << ms(slowest)
        << " ms (" << fixed(1000.0 / slowest, 0) << " a second). The thesis: "
        << fixed(claim.fps, 0) << " frames a second, "
        << (1000.0 / r->p95Ms() >= claim.fps ? "reached" : "**not reached**")
        << " by 95 % of the steps here\n";
  }
  if (out.str().empty()) return "";
  return "**Real time (§6.1)**: the thesis ran the shot pyramid of Fig. 6.6 at 25 frames a "
         "second and the clump of Fig. 6.7 at 20, on a 1500 MHz AMD processor. It gives neither "
         "the pyramid's size, nor the clump's number of cubes, nor its time step, and its rate "
         "counts frames drawn; here a frame is one step of Δt alone, drawing not included, and "
         "the scenes are this project's readings (boxsim damped, frictionless, sleeping on):\n\n" +
         out.str() + "\n";
}

/// The peak resident sets measured (RunResult::peakRssKiB), scene by scene.
std::string memory(const std::vector<SceneResults>& scenes) {
  std::ostringstream out;
  const auto mib = [](long kib) { return fixed(static_cast<double>(kib) / 1024.0, 1); };
  for (const SceneResults& s : scenes)
    for (const RunResult& r : s.runs)
      if (r.peakRssKiB >= 0) {
        out << "- " << s.spec.label() << ", " << r.engine << ": " << mib(r.peakRssKiB) << " MiB";
        if (r.startRssKiB >= 0)
          out << " (" << mib(r.peakRssKiB - r.startRssKiB) << " MiB above the same process "
              << "stepping nothing, " << mib(r.startRssKiB) << " MiB)";
        out << "\n";
      }
  if (out.str().empty()) return "";
  return "**Peak memory** (the peak resident set, VmHWM, of a fresh process running the scene "
         "once, untimed, under one engine):\n\n" + out.str() + "\n";
}

/// The cells of a Markdown table row, trimmed, without the outer bars' empty ends.
std::vector<std::string> cellsOf(const std::string& line) {
  std::vector<std::string> cells;
  std::istringstream in(line);
  for (std::string cell; std::getline(in, cell, '|');) {
    const std::size_t first = cell.find_first_not_of(' ');
    const std::size_t last = cell.find_last_not_of(' ');
    cells.push_back(first == std::string::npos ? "" : cell.substr(first, last - first + 1));
  }
  if (!cells.empty()) cells.erase(cells.begin());  // before the first bar
  return cells;
}

/// "after is worse than before" for two printed numbers, larger being worse; a cell that is
/// not a number is never worse.
bool largerPrinted(const std::string& after, const std::string& before) {
  char* endA = nullptr;
  char* endB = nullptr;
  const double a = std::strtod(after.c_str(), &endA), b = std::strtod(before.c_str(), &endB);
  return endA != after.c_str() && endB != before.c_str() && a > b;
}

}  // namespace

BaselinePage parseBaseline(const std::string& text, const std::string& path) {
  BaselinePage page{path, "unknown", {}};
  int scene = -1, engine = -1, penetration = -1, kinetic = -1, asleep = -1;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("- commit: ", 0) == 0 && page.commit == "unknown") page.commit = line.substr(10);
    if (line.rfind("| ", 0) != 0) continue;
    const std::vector<std::string> cells = cellsOf(line);
    if (!cells.empty() && cells[0] == "scene") {
      for (int k = 0; k < static_cast<int>(cells.size()); ++k) {
        const std::string& name = cells[static_cast<std::size_t>(k)];
        if (name == "scene") scene = k;
        if (name == "engine") engine = k;
        if (name.rfind("penetration mean / final / max", 0) == 0) penetration = k;
        if (name.rfind("kinetic energy at end", 0) == 0) kinetic = k;
        if (name.rfind("all asleep from", 0) == 0) asleep = k;
      }
      continue;
    }
    if (std::min({scene, engine, penetration, kinetic, asleep}) < 0 ||
        static_cast<int>(cells.size()) <= std::max({scene, engine, penetration, kinetic, asleep}))
      continue;
    const auto cell = [&](int k) -> const std::string& { return cells[static_cast<std::size_t>(k)]; };
    // "mean / final / max"
    const std::string& pen = cell(penetration);
    const std::size_t slash = pen.find(" / ");
    if (slash == std::string::npos) continue;
    const std::size_t slash2 = pen.find(" / ", slash + 3);
    page.rows[cell(scene) + "|" + cell(engine)] =
        PrintedPhysics{pen.substr(0, slash), pen.substr(slash + 3, slash2 - slash - 3),
                       cell(kinetic), cell(asleep)};
  }
  if (page.rows.empty())
    throw std::invalid_argument("--baseline " + path +
                                ": no table of boxsim_peers' form (a header row starting "
                                "'| scene |' with penetration, kinetic energy and all asleep "
                                "columns); give a docs/benchmarks.md this tool wrote");
  return page;
}

std::string baselineComparison(const std::vector<SceneResults>& scenes, const BaselinePage& baseline) {
  std::ostringstream worse, same;
  int rows = 0, worseRows = 0;
  for (const SceneResults& s : scenes)
    for (const char* name : kBoxsimRows) {
      const RunResult* r = find(s, name);
      const auto found = baseline.rows.find(s.spec.label() + "|" + name);
      if (!r || found == baseline.rows.end()) continue;
      const PrintedPhysics now = printed(r->measures);
      const PrintedPhysics& was = found->second;
      std::vector<std::string> worseIn;
      if (largerPrinted(now.meanPenetration, was.meanPenetration)) worseIn.push_back("mean penetration");
      if (largerPrinted(now.finalPenetration, was.finalPenetration)) worseIn.push_back("final penetration");
      if (largerPrinted(now.kinetic, was.kinetic)) worseIn.push_back("kinetic energy");
      if (was.allAsleep != "never" &&
          (now.allAsleep == "never" || largerPrinted(now.allAsleep, was.allAsleep)))
        worseIn.push_back("all asleep");
      std::ostringstream line;
      line << "- " << s.spec.label() << ", " << name << ": penetration mean " << was.meanPenetration
           << " → " << now.meanPenetration << " mm, final " << was.finalPenetration << " → "
           << now.finalPenetration << " mm; kinetic energy " << was.kinetic << " → " << now.kinetic
           << " J; all asleep from " << was.allAsleep << " → " << now.allAsleep;
      ++rows;
      if (worseIn.empty()) {
        same << line.str() << "\n";
        continue;
      }
      ++worseRows;
      line << ": **worse** (";
      for (std::size_t k = 0; k < worseIn.size(); ++k) line << (k ? ", " : "") << worseIn[k];
      worse << line.str() << ")\n";
    }
  if (rows == 0) return "";
  std::ostringstream out;
  out << "**Physics against the baseline** (the page measured at " << baseline.commit
      << ", `--baseline " << baseline.path << "`; before → after, as the two pages print them): no worse on "
      << rows - worseRows << " of " << rows << " boxsim rows. One run of a chaotic scene (the "
      << "piles, the clumps) moves by more than some of these differences when every box's "
      << "start is nudged by 1 µm/s (`--perturb`): read a worse row beside its spread over "
      << "seeds.\n\n"
      << worse.str() << same.str() << "\n";
  return out.str();
}

std::string stamp(const std::string& sourceDir) {
  const std::time_t now = std::time(nullptr);
  char date[64];
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  std::string commit = firstLineOf("git -C '" + sourceDir + "' rev-parse --short HEAD 2>/dev/null");
  if (commit.empty()) commit = "unknown";
  // The comparison's own outputs (the last run's pages, data and figure) do not count.
  else if (!firstLineOf("git -C '" + sourceDir + "' status --porcelain --untracked-files=no -- . "
                        "':!docs/benchmarks.md' ':!docs/shot_impact.md' ':!docs/data' "
                        "':!docs/images/s7_peers_scaling.png' 2>/dev/null").empty())
    commit += " with uncommitted changes";
  std::ostringstream out;
  out << "- date: " << date << "\n- commit: " << commit << "\n- machine: "
      << procField("/proc/cpuinfo", "model name") << ", " << std::thread::hardware_concurrency()
      << " logical cores, " << procField("/proc/meminfo", "MemTotal") << "\n- compiler: "
#ifdef __VERSION__
      << "g++ " << __VERSION__
#endif
      << ", " << BOXSIM_BUILD_TYPE << " build\n";
  return out.str();
}

std::string markdownPage(const std::vector<SceneResults>& scenes, const RunSetup& setup,
                         const std::string& stampText) {
  std::ostringstream out;
  out << "# boxsim side by side with Bullet and ODE\n\n"
      << "Written by `boxsim_peers` (bench/peers); do not edit by hand. Regenerate with\n"
      << "`cmake --build build --target bench_peers`.\n\n" << stampText << "- command: `"
      << setup.command << "`\n\n"
      << "## How it is measured\n\n"
      << "One process, one thread (boxsim's rows marked *2 threads* aside; Bullet and ODE step on "
      << "one thread as the harness calls them, btDiscreteDynamicsWorld and dWorldQuickStep with "
      << "no threading implementation), Δt = " << fixed(setup.dt, 6)
      << " s, "
      << (std::any_of(scenes.begin(), scenes.end(), [](const SceneResults& s) { return s.spec.userFile; })
              ? "the page's scenes of 1 kg unit cubes and the boxes of each scene file as it gives them"
              : "1 kg unit cubes")
      << ". Each scene runs "
      << setup.reps << " times under every engine, interleaved (engine A repetition 1, engine B "
      << "repetition 1, …). A step's time is the wall-clock time of the engine's step alone. "
      << "**Mean** ms/step is over every step of every repetition; median and 95th percentile "
      << "beside it; *rep means* is the range of the repetitions' means (the machine's noise). "
      << "The ratio column is the row's mean divided by boxsim damped integration's mean in the "
      << "same scene: above 1, boxsim is faster. Simulated time: " << durations(scenes)
      << " (the pyramids are shot at 5 s). Sleeping (each engine's own: boxsim's §4.5, "
      << "Bullet's deactivation, ODE's auto-disable) is on unless the scene says `sleep off`.\n\n"
      << "The physics is measured on the first repetition with one yardstick for every engine, "
      << "boxsim's separating-axis test on the engine's poses: penetration is the deepest overlap "
      << "of any two boxes (ground included) in a frame, averaged over the frames (scenes of over "
      << "2000 boxes: every 10th frame), after the last step, and the largest of any frame; the "
      << "kinetic energy after the last step; the boxes the engine holds asleep at the end; from "
      << "when every box stays asleep (engine's own sleeping) and from when every box stays at "
      << "rest (below " << kRestSpeed << " m/s and " << kRestSpin << " rad/s, whatever the engine "
      << "does); drift is the tower's top box's distance from its start, or the die's horizontal "
      << "travel. *Work* (boxsim's rows, counted over the first repetition's steps that had a "
      << "body awake): separating-axis tests run per pair in contact at a step's end, per step "
      << "(in brackets: of those, the tests in the passes, of pairs with a fast body at their "
      << "predicted poses; then the tests handed back for poses that had not changed since they "
      << "were run, KeptNarrowPhase); after the plus, the one-axis checks that answered for a "
      << "test, a pair apart along the axis of its last test (separatedBeyond), per pair in "
      << "contact per step; and collision and contact passes per step.\n\n"
      << "## Summary\n\n" << summary(scenes) << aims(scenes)
      << (setup.baseline ? baselineComparison(scenes, *setup.baseline) : "")
      << stages(scenes) << coresModel(scenes) << realTime(scenes) << memory(scenes)
      << "## Table\n\n"
      << "| scene | boxes | engine | mean ms/step | median | p95 | rep means | mean ÷ boxsim damped's "
      << "| penetration mean / final / max (mm) | kinetic energy at end (J) | asleep at end "
      << "| all asleep from (s) | all at rest from (s) | drift (mm) | work |\n"
      << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const SceneResults& s : scenes)
    for (const RunResult& r : s.runs) out << tableRow(s, r);
  out << "\n## Engines\n\n";
  for (const auto& [name, text] : setup.settings) out << "- **" << name << "**: " << text << "\n";
  if (!setup.absent.empty()) out << "- not found at configure time: " << setup.absent << "\n";
  out << "\nFriction: Bullet and ODE run with Coulomb friction μ = " << fixed(scenes.empty() ? 0.5 : scenes.front().spec.friction, 2)
      << " on every contact (Bullet combines two bodies' coefficients by their product, so each "
      << "body gets the square root). *boxsim damped* is the thesis' damped integration, "
      << "frictionless (its damping stands in for friction, §5.2), so a sliding or tumbling box "
      << "travels further under it; *boxsim damped μ* is the same with the peers' Coulomb "
      << "friction on every box (the impulse chapter, \"Coulomb friction\"); *boxsim damped chatter* "
      << "is the frictionless one with chatter detected from history, which puts bodies whose "
      << "last half second went nowhere to sleep (§6.3.1; the impulse chapter, \"Chatter detected "
      << "from history\"); *boxsim damped under load* is the frictionless one whose geometric "
      << "stability also holds boxes that the loads they carry keep in place (§6.3.1, Figs. 6.4 and "
      << "6.5; the geometric stability chapter, \"Stability under load\"); *boxsim damped impact* "
      << "and *boxsim damped μ impact* are the first two with up to 20 collision passes after the "
      << "thesis' five while a pass still stops an impact (the impulse chapter, \"Landings: impact "
      << "passes\"; off by default); *boxsim damped supported impact* is the frictionless one with "
      << "impact passes whose damping acts only on bodies that a chain of contacts joins to the "
      << "ground, so that boxes touching in free fall are not slowed (the impulse chapter, "
      << "\"Damping in flight\"; off by default).\n";
  return out.str();
}

std::string scalingData(const std::vector<SceneResults>& scenes, double restitution,
                        const RunSetup& setup, const std::string& stampText) {
  std::ostringstream out;
  out << "# s7_peers_scaling: ms per step against cubes in the clump of Fig. 6.7, restitution "
      << restitution << ", written by boxsim_peers\n";
  std::istringstream lines(stampText);
  for (std::string line; std::getline(lines, line);) out << "# " << line.substr(2) << "\n";
  out << "# dt: " << setup.dt << " s, repetitions: " << setup.reps << "\n"
      << "# columns: boxes engine mean_ms median_ms p95_ms rep_min_ms rep_max_ms seconds\n";
  for (const SceneResults& s : scenes) {
    // The clumps of the scaling: "clump" and a count, not the named readings such as
    // clump100_ground.
    const bool sized = s.spec.base.rfind("clump", 0) == 0 && s.spec.base.find('_') == std::string::npos;
    if (!sized || s.spec.restitution != restitution || !s.spec.sleep) continue;
    for (const RunResult& r : s.runs) {
      const auto [lo, hi] = std::minmax_element(r.repMeanMs.begin(), r.repMeanMs.end());
      out << r.measures.bodies << " \"" << r.engine << "\" " << r.meanMs() << " " << r.medianMs()
          << " " << r.p95Ms() << " " << *lo << " " << *hi << " " << s.spec.duration << "\n";
    }
  }
  return out.str();
}

}  // namespace boxsim::peers
