// Reproduction driver of the filtering chapter (thesis §5.5, §6.1).
//
// Runs the chattering scenes under the plain impulse-based step ("impulse": the die, the clump
// of Fig. 6.7 and the pyramid of Fig. 6.6), filters every run with the box filter and the
// envelope filter (src/boxsim/filtering/), and writes the data of the chapter's figures into
// the output folder, each file whole or not at all: time series of one body raw and filtered,
// the measures of trajectory_measures.hpp for every scene and filter, the measures against the
// box filter's width, and a combined trajectory with the three versions of the die side by side
// for `boxsim render`. Writes data only; every number is deterministic.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "boxsim/filtering/box_filter.hpp"
#include "boxsim/filtering/envelope_filter.hpp"
#include "boxsim/filtering/orientation_average.hpp"
#include "boxsim/filtering/trajectory_measures.hpp"
#include "boxsim/io/atomic_file.hpp"
#include "boxsim/io/scene.hpp"
#include "boxsim/io/simulate.hpp"
#include "boxsim/io/trajectory.hpp"
#include "boxsim/techniques.hpp"

namespace {

using namespace boxsim;

constexpr double kDt = 1.0 / 60.0;

/// A chattering scene: its raw run under the plain impulse step, its two filtered versions,
/// and the windows the measures look at.
struct SceneRun {
  std::string name;
  Trajectory raw;
  Trajectory box;
  Trajectory envelope;
  double restFrom = 0.0, restTo = 0.0;      ///< s: the window where resting bodies are sought
  double impactFrom = 0.0, impactTo = 0.0;  ///< s: a window with collisions
  std::size_t body = 0;                     ///< the body whose time series is plotted
};

Trajectory runImpulse(const std::string& sceneDir, const std::string& scene, double duration) {
  const std::string path = sceneDir + "/" + scene + ".json";
  Scene s = loadScene(path);
  std::unique_ptr<Stepper> stepper = makeStepper("impulse");
  Recorder recorder(s.world, runParameters(*stepper, s.world, path, kDt, duration));
  SimulateOptions options;
  options.dt = kDt;
  options.duration = duration;
  simulate(s.world, *stepper, options, recorder);
  return recorder.trajectory();
}

SceneRun makeRun(const std::string& sceneDir, const std::string& scene, double duration) {
  SceneRun run;
  run.name = scene;
  run.raw = runImpulse(sceneDir, scene, duration);
  run.box = boxFilter(run.raw);
  run.envelope = envelopeFilter(run.raw);
  return run;
}

std::size_t bodyNamed(const Trajectory& t, const std::string& name) {
  for (std::size_t b = 0; b < t.bodies.size(); ++b)
    if (t.bodies[b].name == name) return b;
  throw std::runtime_error("no body named '" + name + "'");
}

/// The tilt of a box: the angle between world y and the body axis closest to it, rad (0 when
/// a face is flat, up to 0.955 rad).
double tilt(const Quat& q) {
  const Mat3 R = q.toRotationMatrix();
  const double c = R.row(1).cwiseAbs().maxCoeff();
  return std::acos(std::min(1.0, c));
}

/// The common header: the scenes, the method and the filters' parameters.
std::string header(const std::string& title, const SceneRun& any) {
  std::string out = "# " + title + "\n# method: impulse (default parameters), dt: 1/60 s, scenes: chapters/impulse_damped/scenes/\n";
  for (const auto& [key, value] : any.box.meta)
    if (key.rfind("box_", 0) == 0) out += "# " + key + ": " + value + "\n";
  for (const auto& [key, value] : any.envelope.meta)
    if (key.rfind("envelope_", 0) == 0) out += "# " + key + ": " + value + "\n";
  return out;
}

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", value);
  return text;
}

/// Height and tilt of one body, raw, box-filtered and envelope-filtered, every frame.
void writeSeries(const SceneRun& run, const std::string& stem, const std::string& dir) {
  std::string out = header(stem + ": " + run.name + ", body '" + run.raw.bodies[run.body].name +
                               "', raw and filtered", run);
  out += "# rest_window_s: " + number(run.restFrom) + " " + number(run.restTo) + "\n";
  out += "# impact_window_s: " + number(run.impactFrom) + " " + number(run.impactTo) + "\n";
  out += "# columns: t_s raw_y_m box_y_m envelope_y_m raw_tilt_rad box_tilt_rad envelope_tilt_rad raw_x_m box_x_m envelope_x_m\n";
  const std::size_t b = run.body;
  for (std::size_t k = 0; k < run.raw.frames.size(); ++k) {
    out += number(run.raw.frames[k].t);
    for (const Trajectory* t : {&run.raw, &run.box, &run.envelope}) out += " " + number(t->frames[k].x[b].y());
    for (const Trajectory* t : {&run.raw, &run.box, &run.envelope}) out += " " + number(tilt(t->frames[k].q[b]));
    for (const Trajectory* t : {&run.raw, &run.box, &run.envelope}) out += " " + number(t->frames[k].x[b].x());
    out += "\n";
  }
  writeFileAtomically(dir + "/" + stem + ".dat", out);
}

/// Every measure of one displayed version of a run.
struct Measures {
  MotionMeasures motion;
  PopMeasure pop;
  OverlapMeasure overlap;     ///< deepest overlap over the whole run
  OverlapMeasure introduced;  ///< overlap introduced by the filter over the whole run
  PeakAcceleration peak;
};

Measures measure(const SceneRun& run, const Trajectory& displayed) {
  Measures m;
  const FrameWindow rest = frameWindow(run.raw, run.restFrom, run.restTo);
  const FrameWindow impact = frameWindow(run.raw, run.impactFrom, run.impactTo);
  const FrameWindow all{0, run.raw.frames.size()};
  const std::vector<std::size_t> resting = restingBodies(run.raw, rest);
  m.motion = motionMeasures(displayed, rest, resting);
  m.pop = pops(displayed, rest, resting);
  m.overlap = deepestOverlap(displayed, all);
  m.introduced = overlapIntroduced(run.raw, displayed, all);
  m.peak = peakAcceleration(displayed, impact, movableBodies(run.raw));
  return m;
}

void writeMeasures(const std::vector<SceneRun>& runs, const std::string& dir) {
  std::string out = header("s5_5_measures: the measures of trajectory_measures.hpp, raw and filtered", runs.front());
  out += "# chatter, squirm and pops: resting bodies (RestingParams defaults) over the rest window; overlaps: "
         "every pair over the whole run; peak acceleration: every movable body over the impact window\n";
  for (const SceneRun& r : runs)
    out += "# " + r.name + ": duration " + number(r.raw.frames.back().t) + " s, rest window " +
           number(r.restFrom) + "-" + number(r.restTo) + " s, impact window " + number(r.impactFrom) +
           "-" + number(r.impactTo) + " s\n";
  out += "# columns: index scene filter resting_bodies chatter_position_m2 chatter_angle_rad2 squirm_position_m_per_s "
         "squirm_angle_rad_per_s pop_position_m pop_angle_rad overlap_box_box_m overlap_box_ground_m "
         "overlap_introduced_box_box_m overlap_introduced_box_ground_m "
         "peak_acceleration_m_per_s2 peak_angular_acceleration_rad_per_s2 peak_acceleration_over_raw "
         "displayed_speed_position_m_per_s squirm_share_position\n";
  int index = 0;
  for (const SceneRun& r : runs) {
    const char* names[] = {"raw", "box", "envelope"};
    const Trajectory* versions[] = {&r.raw, &r.box, &r.envelope};
    const double rawPeak = measure(r, r.raw).peak.linear;
    for (int v = 0; v < 3; ++v) {
      const Measures m = measure(r, *versions[v]);
      out += std::to_string(index++) + " " + r.name + " " + names[v] + " " + std::to_string(m.motion.bodies);
      for (double value : {m.motion.chatterPosition, m.motion.chatterAngle, m.motion.squirmPosition,
                           m.motion.squirmAngle, m.pop.position, m.pop.angle, m.overlap.boxBox,
                           m.overlap.boxGround, m.introduced.boxBox, m.introduced.boxGround, m.peak.linear,
                           m.peak.angular, m.peak.linear / rawPeak, m.motion.displayedSpeedPosition,
                           m.motion.squirmSharePosition()})
        out += " " + number(value);
      out += "\n";
    }
    out += "\n";
  }
  writeFileAtomically(dir + "/s5_5_measures.dat", out);
}

/// The box filter's trade-off (§5.5: a wider kernel cuts squirm but loses sharp collisions):
/// the measures of box-filtered runs against the half width H.
void writeWidthSweep(const std::vector<SceneRun>& runs, const std::string& dir) {
  std::string out = header("s5_5_width_sweep: box filter measures against the half width H", runs.front());
  out += "# ratios are box-filtered over raw; overlap_introduced: overlapIntroduced(), box-box and box-ground, m\n# columns: H";
  for (const SceneRun& r : runs)
    out += " " + r.name + "_chatter_ratio " + r.name + "_squirm_m_per_s " + r.name + "_peak_ratio " + r.name +
           "_overlap_introduced_m";
  out += "\n";
  std::vector<Measures> raw;
  for (const SceneRun& r : runs) raw.push_back(measure(r, r.raw));
  for (int h : {0, 1, 2, 3, 4, 6, 8, 12, 16}) {
    out += std::to_string(h);
    for (std::size_t i = 0; i < runs.size(); ++i) {
      BoxFilterParams p;
      p.halfWidth = h;
      const Measures m = measure(runs[i], boxFilter(runs[i].raw, p));
      const double chatterRatio = raw[i].motion.bodies > 0 ? m.motion.chatterPosition / raw[i].motion.chatterPosition : NAN;
      const double squirm = raw[i].motion.bodies > 0 ? m.motion.squirmPosition : NAN;
      out += " " + number(chatterRatio) + " " + number(squirm) + " " + number(m.peak.linear / raw[i].peak.linear) + " " +
             number(std::max(m.introduced.boxBox, m.introduced.boxGround));
    }
    out += "\n";
  }
  writeFileAtomically(dir + "/s5_5_width_sweep.dat", out);
}

/// The three versions of a run in one trajectory: raw, box and envelope copies of every body
/// (renamed raw_*, box_*, env_*), shifted along x by -offset, 0 and +offset m; the immovable
/// bodies once. Frames [from, to] s.
Trajectory sideBySide(const SceneRun& run, double offset, double from, double to) {
  Trajectory out;
  out.meta = run.raw.meta;
  out.meta["side_by_side"] = "raw_ at x - " + number(offset) + " m, box_ at x, env_ at x + " + number(offset) + " m";
  const char* prefixes[] = {"raw_", "box_", "env_"};
  const Trajectory* versions[] = {&run.raw, &run.box, &run.envelope};
  std::vector<std::pair<int, std::size_t>> source;  // (version, body)
  for (std::size_t b = 0; b < run.raw.bodies.size(); ++b)
    if (run.raw.bodies[b].immovable) {
      out.bodies.push_back(run.raw.bodies[b]);
      source.push_back({0, b});
    }
  for (int v = 0; v < 3; ++v)
    for (std::size_t b = 0; b < run.raw.bodies.size(); ++b)
      if (!run.raw.bodies[b].immovable) {
        TrajectoryBody body = run.raw.bodies[b];
        body.name = prefixes[v] + body.name;
        out.bodies.push_back(body);
        source.push_back({v, b});
      }
  for (std::size_t k = 0; k < run.raw.frames.size(); ++k) {
    const TrajectoryFrame& f = run.raw.frames[k];
    if (f.t < from - 1e-9 || f.t > to + 1e-9) continue;
    TrajectoryFrame g = f;
    g.x.clear();
    g.q.clear();
    for (const auto& [v, b] : source) {
      const TrajectoryFrame& src = versions[v]->frames[k];
      const double shift = run.raw.bodies[b].immovable ? 0.0 : (v - 1) * offset;
      g.x.push_back(src.x[b] + Vec3(shift, 0.0, 0.0));
      g.q.push_back(src.q[b]);
    }
    out.frames.push_back(g);
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Data of the filtering chapter's figures (thesis §5.5)"};
  std::string scenes = "chapters/impulse_damped/scenes";
  std::string out = ".";
  app.add_option("--scenes", scenes, "Folder of the scene files")->capture_default_str();
  app.add_option("--out", out, "Folder the .dat files are written to")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    std::vector<SceneRun> runs;
    runs.push_back(makeRun(scenes, "die", 12.0));
    runs.back().restFrom = 10.5, runs.back().restTo = 12.0;
    runs.back().impactFrom = 0.35, runs.back().impactTo = 0.75;
    runs.back().body = bodyNamed(runs.back().raw, "die");
    runs.push_back(makeRun(scenes, "clump100", 5.0));
    runs.back().restFrom = 3.0, runs.back().restTo = 5.0;
    runs.back().impactFrom = 1.5, runs.back().impactTo = 3.0;
    runs.back().body = 1;
    runs.push_back(makeRun(scenes, "pyramid10_shot", 7.0));
    runs.back().restFrom = 1.0, runs.back().restTo = 4.5;
    runs.back().impactFrom = 4.9, runs.back().impactTo = 5.6;
    runs.back().body = runs.back().raw.bodies.size() - 2;
    for (const SceneRun& r : runs) {
      const FrameWindow rest = frameWindow(r.raw, r.restFrom, r.restTo);
      std::cout << "filtering: " << r.name << ": " << r.raw.frames.size() << " frames, "
                << restingBodies(r.raw, rest).size() << " resting bodies in " << r.restFrom << "-" << r.restTo
                << " s\n";
    }
    writeSeries(runs[0], "s5_5_die_filtered", out);
    writeSeries(runs[1], "s5_5_clump_filtered", out);
    writeSeries(runs[2], "s5_5_pyramid_filtered", out);
    writeMeasures(runs, out);
    writeWidthSweep(runs, out);
    writeTrajectory(out + "/s5_5_side_by_side.dat", sideBySide(runs[0], 1.8, 7.4, 10.4));
  } catch (const std::exception& e) {
    std::cerr << "filtering_figures: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
