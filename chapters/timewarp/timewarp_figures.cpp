// Reproduction driver of the timewarp chapter (thesis §2.4.3, §5.1, Alg. A.1).
//
// Writes the data of the chapter's figures into the output folder, each file whole or not at
// all, and renders the 3D frames itself: the order in which SIMPLESYNCTIMEWARP,
// SAFERSYNCTIMEWARP and the swept variant resolve the collisions of Fig. 5.1's row, against
// the chronological order of a fine-stepped basic colliding run; frames of that run; and the
// work and time one frame costs when k independent pairs collide at different instants, under
// the basic colliding technique (every collision rolls every body back, §2.4.3) and under the
// three timewarps (only the colliding pair is rolled back, §5.1). Timings are measurements of
// this machine; every count is deterministic.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "boxsim/basic_colliding/basic_colliding.hpp"
#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/io/atomic_file.hpp"
#include "boxsim/io/recorder.hpp"
#include "boxsim/io/render.hpp"
#include "boxsim/io/scene_builders.hpp"
#include "boxsim/techniques.hpp"
#include "boxsim/timewarp/timewarp.hpp"

namespace {

using namespace boxsim;

constexpr double kDt = 1.0 / 60.0;
/// The reference's small step (s), and its time-of-impact tolerance (s): far below the gaps
/// between Fig. 5.1's true collision times (the closest two, C-D and D-E, are 0.1 ms apart).
constexpr double kReferenceStep = 1e-5;
constexpr double kReferenceTolerance = 1e-8;

/// The number of small steps the reference divides the frame into: ceil(kDt / kReferenceStep).
long referenceSteps() { return static_cast<long>(std::ceil(kDt / kReferenceStep - 1e-9)); }

constexpr TimewarpVariant kVariants[] = {TimewarpVariant::Simple, TimewarpVariant::Safer,
                                         TimewarpVariant::Swept};

/// One resolved collision: its time (s after the frame's start) and its pair, a < b.
struct Event {
  double time = 0.0;
  int a = -1;
  int b = -1;
};

/// The events one method resolved in Fig. 5.1's frame, in the order it resolved them, and the
/// world at the end of the frame.
struct OrderRun {
  std::string method;
  std::vector<Event> events;
  World end;
};

/// Fig. 5.1's row A..E (scene_builders.hpp) as the figure means it: no gravity, perfectly
/// elastic collisions, so the true sequence is a Newton's cradle A→B→C→D→E and then C→D.
/// No ground: nothing falls, and the renderer draws a world without a floor.
World fig5_1World() {
  World world;
  world.gravity = Vec3::Zero();
  world.restitution = 1.0;
  addFig5_1Row(world);
  return world;
}

std::string pairName(const World& world, int a, int b) { return world.names[a] + "-" + world.names[b]; }

/// "A-B@0.00139 B-C@0.00278 ...": the events of a run in the order given.
std::string orderText(const OrderRun& run) {
  std::string text;
  for (const Event& e : run.events) {
    char time[32];
    std::snprintf(time, sizeof time, "@%.5f", e.time);
    text += (text.empty() ? "" : " ") + pairName(run.end, e.a, e.b) + time;
  }
  return text;
}

/// "A 0 B 0 C 0 D 6 E 144": every body's x velocity (m/s) at the end of a run.
std::string finalVelocities(const World& world) {
  std::string text;
  for (std::size_t k = 0; k < world.bodies.size(); ++k) {
    char v[48];
    std::snprintf(v, sizeof v, "%s%s %.4g", k ? " " : "", world.names[k].c_str(),
                  world.bodies[k].v.x() + 0.0);
    text += v;
  }
  return text;
}

/// "0.8 A-B": the deepest overlap (m) of any pair at the end of a run and its pair, or "0".
std::string deepestOverlap(const World& world) {
  const std::vector<ContactManifold> contacts = findContacts(world, 1e-3);
  const ContactManifold* deepest = nullptr;
  for (const ContactManifold& m : contacts)
    if (m.depth > 0.0 && (!deepest || m.depth > deepest->depth)) deepest = &m;
  if (!deepest) return "0";
  char text[64];
  std::snprintf(text, sizeof text, "%.3g ", deepest->depth);
  return text + pairName(world, deepest->a, deepest->b);
}

/// The chronological reference of Fig. 5.1 (§2.1's basic colliding technique, which rolls the
/// whole world back to each collision in time order): the frame in n small steps of kDt / n
/// s, n = referenceSteps(), time-of-impact tolerance kReferenceTolerance. Every
/// small step that changes the velocities of exactly two bodies is one event of that pair,
/// dated at the end of the step. Poses are captured into `recorder` at the steps nearest to
/// `instants` (s).
OrderRun referenceRun(Recorder& recorder, const std::vector<double>& instants) {
  BasicCollidingParams params;
  params.timeOfImpact.timeTolerance = kReferenceTolerance;
  BasicCollidingStepper stepper(params);
  OrderRun run{"reference", {}, fig5_1World()};
  World& world = run.end;
  const long n = referenceSteps();
  const double h = kDt / static_cast<double>(n);
  std::size_t nextInstant = 0;
  const auto captureDue = [&](long step) {
    while (nextInstant < instants.size() && std::lround(instants[nextInstant] / h) <= step) {
      recorder.capture(world, static_cast<double>(step) * h);
      ++nextInstant;
    }
  };
  captureDue(0);
  for (long step = 1; step <= n; ++step) {
    const std::vector<RigidBody> before = world.bodies;
    stepper.step(world, h);
    std::vector<int> changed;
    for (std::size_t k = 0; k < world.bodies.size(); ++k)
      if ((world.bodies[k].v - before[k].v).norm() > 1e-9 ||
          (world.bodies[k].omega - before[k].omega).norm() > 1e-9)
        changed.push_back(static_cast<int>(k));
    if (changed.size() == 2) {
      run.events.push_back({static_cast<double>(step) * h, changed[0], changed[1]});
    } else if (!changed.empty()) {
      throw std::runtime_error("reference: a step of " + std::to_string(h) + " s changed " +
                               std::to_string(changed.size()) +
                               " bodies' velocities; the pair of the event is ambiguous");
    }
    captureDue(step);
  }
  return run;
}

/// One frame of Fig. 5.1 under a timewarp variant; fixInterpenetration (SIMPLESYNCTIMEWARP L22, SAFERSYNCTIMEWARP L33)
/// off,
/// so the end state shows what the event order did.
OrderRun timewarpRun(TimewarpVariant variant) {
  TimewarpParams params;
  params.variant = variant;
  params.fixInterpenetration = false;
  TimewarpStepper stepper(params);
  OrderRun run{timewarpMethodName(variant), {}, fig5_1World()};
  stepper.step(run.end, kDt);
  for (const TimewarpEvent& e : stepper.lastEvents()) run.events.push_back({e.time, e.a, e.b});
  return run;
}

/// The label level of each event in a timeline row: the lowest level no earlier-resolved event
/// within `window` s occupies, so labels of near-simultaneous events stack instead of overlap.
std::vector<int> labelLevels(const std::vector<Event>& events, double window) {
  std::vector<int> levels;
  for (std::size_t i = 0; i < events.size(); ++i) {
    const auto taken = [&](int level) {
      for (std::size_t j = 0; j < i; ++j)
        if (levels[j] == level && std::abs(events[j].time - events[i].time) < window) return true;
      return false;
    };
    int level = 0;
    while (taken(level)) ++level;
    levels.push_back(level);
  }
  return levels;
}

/// Fig. 5.1: the event order of the reference and of the three timewarp variants, and the
/// frames of the reference run and the end states of all four, rendered.
void writeEventOrder(const std::string& out) {
  const World row = fig5_1World();
  const std::vector<double> instants = {0.0, 0.002, 0.004, 0.006, kDt};
  Recorder strip(row, {{"scene", "fig5_1_row"}, {"method", "basic_colliding"}});
  std::vector<OrderRun> runs;
  runs.push_back(referenceRun(strip, instants));
  for (const TimewarpVariant v : kVariants) runs.push_back(timewarpRun(v));

  std::ostringstream text;
  text << "# fig5_1_event_order: Fig. 5.1's row A..E (addFig5_1Row), gravity 0, restitution 1, "
          "one frame of 1/60 s\n"
       << "# reference: basic_colliding, time_tolerance " << kReferenceTolerance
       << " s, " << referenceSteps() << " steps of " << kDt / static_cast<double>(referenceSteps())
       << " s; an event wherever a step changes two bodies' velocities, dated at the step's end\n"
       << "# timewarp: resolution " << TimewarpParams{}.resolution
       << " s, fix_interpenetration off\n";
  for (const OrderRun& run : runs) {
    text << "# order_" << run.method << ": " << orderText(run) << "\n";
    text << "# final_vx_" << run.method << ": " << finalVelocities(run.end) << "\n";
    text << "# deepest_overlap_m_" << run.method << ": " << deepestOverlap(run.end) << "\n";
  }
  text << "# columns: row method order time_ms pair label_level\n";
  // One block per method, top row first, separated by two blank lines (gnuplot's index).
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const OrderRun& run = runs[r];
    const std::vector<int> levels = labelLevels(run.events, 1.2e-3);
    for (std::size_t i = 0; i < run.events.size(); ++i) {
      const Event& e = run.events[i];
      char line[128];
      std::snprintf(line, sizeof line, "%zu %s %zu %.5f %s %d\n", runs.size() - 1 - r,
                    run.method.c_str(), i + 1, 1e3 * e.time, pairName(run.end, e.a, e.b).c_str(),
                    levels[i]);
      text << line;
    }
    text << "\n\n";
  }
  writeFileAtomically(out + "/fig5_1_event_order.dat", text.str());

  RenderOptions options;
  options.width = 360;
  options.height = 240;
  options.title = "Fig. 5.1, chronological reference: t = 0, 2, 4, 6, 16.7 ms (A left, E right)";
  for (int f = 0; f < static_cast<int>(strip.trajectory().frames.size()); ++f)
    options.frames.push_back(f);
  for (const char* kind : {".png", ".svg"})
    renderTrajectory(strip.trajectory(), out + "/fig5_1_row_strip" + kind, options);

  // The four end states side by side, in one recording: every world has the same bodies.
  Recorder ends(row, {{"scene", "fig5_1_row"}});
  for (const OrderRun& run : runs) ends.capture(run.end, kDt);
  options.frames = {0, 1, 2, 3};
  options.title = "End of the frame (t = 1/60 s): reference, timewarp simple, safer, swept";
  for (const char* kind : {".png", ".svg"})
    renderTrajectory(ends.trajectory(), out + "/fig5_1_end_states" + kind, options);
}

/// §2.4.3's case for the timewarp: k independent pairs of unit cubes of 1 kg
/// (addApproachingPairs: pair i at z = 10 i m, faces 1 + i / k m apart, approaching along x at
/// 3 m/s each), so the pairs collide once each, at distinct instants spread over
/// 0.17-0.33 s, inside 30 frames. Gravity 0, restitution 1, no ground.
World pairsWorld(int k) {
  World world;
  world.gravity = Vec3::Zero();
  world.restitution = 1.0;
  addApproachingPairs(world, k, 10.0, 1.0, 3.0);
  return world;
}

/// The methods compared, by name (techniques.hpp): the basic colliding technique and the three
/// timewarps, each with its default parameters (the timewarps with FIXINTERPENETRATION on, as
/// A.1 runs them).
const std::vector<std::string> kCostMethods = {"basic_colliding", "timewarp_simple",
                                               "timewarp_safer", "timewarp_swept"};

/// The summed StepStats of 30 frames of pairsWorld(k) under one method, and the wall time per
/// frame (ms), the run repeated until at least 50 ms of stepping so the clock's resolution
/// does not matter.
struct CostResult {
  StepStats sum;
  double msPerFrame = 0.0;
};

CostResult measureCost(int k, const std::string& method, int frames) {
  const World start = pairsWorld(k);
  CostResult result;
  double elapsed = 0.0;
  int repetitions = 0;
  do {
    World world = start;
    std::unique_ptr<Stepper> stepper = makeStepper(method);
    StepStats sum;
    const auto begin = std::chrono::steady_clock::now();
    for (int f = 0; f < frames; ++f) sum += stepper->step(world, kDt);
    elapsed += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin).count();
    if (repetitions++ == 0) result.sum = sum;
  } while (elapsed < 50.0);
  result.msPerFrame = elapsed / (repetitions * frames);
  return result;
}

void writeCost(const std::string& out) {
  const int frames = 30;
  std::ostringstream text;
  text << "# s5_1_cost: k pairs of unit cubes colliding once each at distinct instants (pair i at "
          "z = 10 i m, 3 m/s each, faces 1 + i / k m apart: addApproachingPairs), gravity 0, restitution 1, "
          "no ground; "
       << frames << " frames of 1/60 s, default parameters, one thread, this machine\n"
       << "# frames: " << frames << "\n"
       << "# methods: basic_colliding timewarp_simple timewarp_safer timewarp_swept\n"
       << "# columns: k, then per method: body_integrations body_rollbacks bisections events "
          "(sums over the frames) ms_per_frame\n";
  for (const int k : {1, 2, 4, 8, 16, 32, 64}) {
    text << k;
    for (const std::string& method : kCostMethods) {
      const CostResult r = measureCost(k, method, frames);
      char cells[160];
      std::snprintf(cells, sizeof cells, " %ld %ld %d %d %.5g", r.sum.bodyIntegrations,
                    r.sum.bodyRollbacks, r.sum.bisections, r.sum.events, r.msPerFrame);
      text << cells;
    }
    text << "\n";
  }
  writeFileAtomically(out + "/s5_1_cost.dat", text.str());
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Data and frames of the timewarp chapter's figures"};
  std::string out = ".";
  app.add_option("--out", out, "Folder the .dat files and images are written to")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    writeEventOrder(out);
    writeCost(out);
  } catch (const std::exception& e) {
    std::cerr << "timewarp_figures: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
