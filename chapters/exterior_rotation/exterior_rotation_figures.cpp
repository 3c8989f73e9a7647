// Reproduction driver of the exterior rotation chapter (thesis §6.2, Figs. 6.1-6.3).
//
// Writes the data of the chapter's figures into the output folder, each file whole or not at
// all, and renders the 3D strips itself: the drift of the sticking contacts of Figs. 6.1-6.3
// against time under each integrator at dt = 1/60 s; the largest drift over each scene's
// window against dt, with fitted slopes; the top box's path of Fig. 6.1 against its circle;
// the cost of one step of each integrator; and Figs. 6.2 and 6.3 under the thesis' own model,
// frictionless unilateral LCP forces held by forward Euler. Timings are measurements of this
// machine; every other number is deterministic.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "boxsim/exterior_rotation/sticking_run.hpp"
#include "boxsim/exterior_rotation/unilateral_run.hpp"
#include "boxsim/io/atomic_file.hpp"
#include "boxsim/io/recorder.hpp"
#include "boxsim/io/render.hpp"

namespace {

using namespace boxsim;

constexpr double kDt = 1.0 / 60.0;
/// The steps of the convergence sweep: 1/60 s and four halvings.
const std::vector<double> kSweep = {1.0 / 60.0, 1.0 / 120.0, 1.0 / 240.0, 1.0 / 480.0, 1.0 / 960.0};
/// Below this largest drift (m) a run is at rounding: no slope is fitted.
constexpr double kRoundingLevel = 1e-13;

/// A method's name in the figures' keys.
std::string methodTitle(StickingMethod m) {
  switch (m) {
    case StickingMethod::ForwardEuler: return "forward Euler (thesis)";
    case StickingMethod::SemiImplicitEuler: return "semi-implicit Euler";
    case StickingMethod::RungeKutta4ConstantForces: return "RK4, forces held over the step";
    case StickingMethod::RungeKutta4ResolvedForces: return "RK4, forces re-solved per stage";
    case StickingMethod::ScrewEuler: return "screw Euler";
    case StickingMethod::ScrewEulerProjected: return "screw Euler + projection";
  }
  return "unknown";
}

int stepsOf(const StickingScene& scene, double dt) { return static_cast<int>(std::lround(scene.window / dt)); }

/// "%.6g" of a value, for data rows.
std::string num(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value + 0.0);
  return text;
}

/// The `#` lines every file carries: the scenes and what the signs mean.
std::string commonHeader() {
  std::ostringstream h;
  h << "# scenes (src/boxsim/exterior_rotation/sticking_scene.hpp): table top y = 0, its edge (the pivot) x = y = 0 along z; "
       "gravity 9.81 m/s^2; every contact sticks (bilateral point constraints), forces from solveStickingForces\n";
  for (const StickingScene& s : allStickingScenes())
    h << "# scene " << s.name << " (Fig. " << s.figure << "): window " << shortestText(s.window) << " s, "
      << s.world.movableCount() << " movable bodies, " << s.points.size() << " contact points\n";
  h << "# gap: (p_b - p_a) . n, n the contact normal from a into b: + separated, - interpenetrating\n";
  return h.str();
}

/// fig6_1/6_2/6_3_penetration_vs_time: every measure after every step of dt = 1/60 s, one block
/// per method (its first row the method's title, for gnuplot's columnheader).
void writePenetrationVsTime(const std::string& out, const StickingScene& scene, const std::string& stem) {
  std::ostringstream text;
  text << "# " << stem << ": the sticking contacts of Fig. " << scene.figure << " (" << scene.name
       << ") under each integrator, dt 1/60 s, " << stepsOf(scene, kDt) << " steps\n"
       << commonHeader()
       << "# columns: t_s penetration_m min_gap_m max_gap_m pivot_gap_m hinge_gap_m max_error_m "
          "radial_error_m pivot_normal_N\n"
       << "# pivot_gap: mean gap of the table-edge contact; hinge_gap: of the A-B hinge (Fig. 6.3 only, else 0)\n"
       << "# blocks (gnuplot index): ";
  for (const StickingMethod m : allStickingMethods()) text << stickingMethodName(m) << " ";
  text << "\n";
  for (const StickingMethod m : allStickingMethods()) {
    const StickingRun run = runSticking(scene, m, kDt, stepsOf(scene, kDt));
    text << "\"" << methodTitle(m) << "\" 0 0 0 0 0 0 0 0\n";
    for (const StickingSample& s : run.samples) {
      const double hingeGap = scene.pivots.size() > 1 ? s.contactGap[scene.pivots[1]] : 0.0;
      text << num(s.t) << " " << num(s.penetration) << " " << num(s.minGap) << " " << num(s.maxGap) << " "
           << num(s.contactGap[scene.pivots[0]]) << " " << num(hingeGap) << " " << num(s.maxError) << " "
           << num(s.radialError) << " " << num(s.pivotLoads[0].normal) << "\n";
    }
    text << "\n\n";
  }
  writeFileAtomically(out + "/" + stem + ".dat", text.str());
}

/// s6_2_penetration_vs_dt: the extremes over each scene's window for every dt of the sweep,
/// one block per (scene, method), scene-major; each block's title row carries the fitted slope.
void writeSweep(const std::string& out) {
  std::ostringstream text;
  text << "# s6_2_penetration_vs_dt: the largest drift over each scene's window against dt (1/60 s and four halvings)\n"
       << commonHeader()
       << "# columns: dt_s max_error_m max_penetration_m min_gap_m max_gap_m max_abs_radial_error_m "
          "max_reference_error_m\n"
       << "# max_error: max over points and steps of |p_b - p_a|; slope: least squares of log(max_error) on log(dt) "
          "over the sweep, none when the finest max_error is below "
       << kRoundingLevel << " m (rounding)\n"
       << "# blocks (gnuplot index): scene-major, scenes pivoting_group pivoting_box two_frames, methods ";
  for (const StickingMethod m : allStickingMethods()) text << stickingMethodName(m) << " ";
  text << "\n";
  for (const StickingScene& scene : allStickingScenes()) {
    for (const StickingMethod m : allStickingMethods()) {
      std::vector<double> errors;
      std::vector<StickingSummary> summaries;
      for (const double dt : kSweep) {
        summaries.push_back(runSticking(scene, m, dt, stepsOf(scene, dt)).summary);
        errors.push_back(summaries.back().maxError);
      }
      char title[128];
      const double tolerance = ProjectionParams{}.positionTolerance;
      if (m == StickingMethod::ScrewEulerProjected && *std::max_element(errors.begin(), errors.end()) > kRoundingLevel &&
          *std::max_element(errors.begin(), errors.end()) <= tolerance) {
        std::snprintf(title, sizeof title, "%s: held within its %.0e m tolerance", methodTitle(m).c_str(), tolerance);
      } else if (errors.back() < kRoundingLevel) {
        std::snprintf(title, sizeof title, "%s: rounding (< %.0e m)", methodTitle(m).c_str(), kRoundingLevel);
      } else {
        std::snprintf(title, sizeof title, "%s: slope %.2f", methodTitle(m).c_str(), convergenceOrder(kSweep, errors));
      }
      text << "# slope " << scene.name << " " << stickingMethodName(m) << ": " << title << "\n";
      text << "\"" << title << "\" 0 0 0 0 0 0\n";
      for (std::size_t i = 0; i < kSweep.size(); ++i) {
        const StickingSummary& s = summaries[i];
        text << num(kSweep[i]) << " " << num(s.maxError) << " " << num(s.maxPenetration) << " " << num(s.minGap)
             << " " << num(s.maxGap) << " " << num(s.maxAbsRadialError) << " " << num(s.maxReferenceError) << "\n";
      }
      text << "\n\n";
    }
  }
  writeFileAtomically(out + "/s6_2_penetration_vs_dt.dat", text.str());
}

/// fig6_1_top_box_path: the top box TR of Fig. 6.1 under each integrator at dt = 1/60 s, and the
/// circle it should follow (last block, 200 points of the reference's arc).
void writeTopBoxPath(const std::string& out) {
  const StickingScene scene = pivotingGroup();
  const Vec3 centre0 = scene.world.bodies[scene.topBody].s.x;
  const double radius = centre0.norm();  // the pivot is the origin
  const double angle0 = std::atan2(centre0.y(), centre0.x());
  std::ostringstream text;
  text << "# fig6_1_top_box_path: the top box (TR) of Fig. 6.1, dt 1/60 s, " << stepsOf(scene, kDt) << " steps\n"
       << commonHeader() << "# circle: centre the pivot (0, 0), radius " << radius << " m\n"
       << "# columns: t_s x_m y_m x_reference_m y_reference_m radial_error_m turned_deg\n"
       << "# turned: the reference's rotation of the group, degrees clockwise\n"
       << "# blocks (gnuplot index): ";
  for (const StickingMethod m : allStickingMethods()) text << stickingMethodName(m) << " ";
  text << "circle\n";
  double lastAngle = 0.0;
  for (const StickingMethod m : allStickingMethods()) {
    const StickingRun run = runSticking(scene, m, kDt, stepsOf(scene, kDt));
    text << "\"" << methodTitle(m) << "\" 0 0 0 0 0 0\n";
    for (const StickingSample& s : run.samples) {
      lastAngle = -s.referenceAngles[0];
      text << num(s.t) << " " << num(s.top.x()) << " " << num(s.top.y()) << " " << num(s.topReference.x()) << " "
           << num(s.topReference.y()) << " " << num(s.radialError) << " " << num(lastAngle * 180.0 / kPi) << "\n";
    }
    text << "\n\n";
  }
  text << "\"the circle about the pivot\" 0 0 0 0 0 0\n";
  for (int i = 0; i <= 200; ++i) {
    const double a = angle0 - (lastAngle + 0.1) * i / 200.0;
    text << "0 " << num(radius * std::cos(a)) << " " << num(radius * std::sin(a)) << " 0 0 0 0\n";
  }
  writeFileAtomically(out + "/fig6_1_top_box_path.dat", text.str());
}

/// µs per step of `method` on `scene` at dt = 1/60 s: the whole window stepped, repeated for at
/// least 100 ms so the clock's resolution does not matter.
double microsecondsPerStep(const StickingScene& scene, StickingMethod method) {
  const int steps = stepsOf(scene, kDt);
  StickingScene warmUp = scene;
  for (int k = 0; k < steps; ++k) stepSticking(warmUp, method, kDt);
  const auto start = std::chrono::steady_clock::now();
  long total = 0;
  double elapsed = 0.0;
  do {
    StickingScene s = scene;
    for (int k = 0; k < steps; ++k) stepSticking(s, method, kDt);
    total += steps;
    elapsed = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
  } while (elapsed < 1e5);
  return elapsed / static_cast<double>(total);
}

/// s6_2_cost: µs per step of every method on every scene, and the ratio to forward Euler.
void writeCost(const std::string& out) {
  std::ostringstream text;
  text << "# s6_2_cost: wall time of one step (the sticking solve included), dt 1/60 s, one thread, this machine\n"
       << commonHeader() << "# columns: scene method us_per_step ratio_to_forward_euler\n";
  for (const StickingScene& scene : allStickingScenes()) {
    const double fe = microsecondsPerStep(scene, StickingMethod::ForwardEuler);
    for (const StickingMethod m : allStickingMethods()) {
      const double us = m == StickingMethod::ForwardEuler ? fe : microsecondsPerStep(scene, m);
      char line[160];
      std::snprintf(line, sizeof line, "%s %s %.4g %.3g\n", scene.name.c_str(), stickingMethodName(m).c_str(), us,
                    us / fe);
      text << line;
    }
  }
  writeFileAtomically(out + "/s6_2_cost.dat", text.str());
}

/// The 3D strips: five instants of each scene's window under RK4 with re-solved forces (drift
/// below a micrometre at 1/60 s, so the pictures show the true motion).
void renderStrips(const std::string& out) {
  const std::vector<std::pair<StickingScene, std::string>> strips = {
      {pivotingGroup(), "fig6_1_group_strip"}, {pivotingBox(), "fig6_2_box_strip"}, {twoFrames(), "fig6_3_two_frames_strip"}};
  for (const auto& [scene, stem] : strips) {
    Recorder recorder(scene.world, {{"scene", scene.name}, {"method", "rk4_resolved_forces"}, {"dt", "1/60"}});
    const int steps = stepsOf(scene, kDt);
    int step = 0;
    runSticking(scene, StickingMethod::RungeKutta4ResolvedForces, kDt, steps, [&](const World& world, double t) {
      if ((4 * step) % steps < 4) recorder.capture(world, t);
      ++step;
    });
    RenderOptions options;
    options.width = 300;
    options.height = 260;
    options.groundHalfSize = 0.45;
    char title[160];
    std::snprintf(title, sizeof title, "Fig. %s (%s): sticking contacts, t = 0 to %.2f s", scene.figure.c_str(),
                  scene.name.c_str(), scene.window);
    options.title = title;
    for (int f = 0; f < static_cast<int>(recorder.trajectory().frames.size()); ++f) options.frames.push_back(f);
    renderTrajectory(recorder.trajectory(), out + "/" + stem + ".png", options);
  }
}

}  // namespace

/// s6_2_unilateral and s6_2_unilateral_vs_dt: Figs. 6.2 and 6.3 in the thesis' own model,
/// frictionless unilateral LCP forces held over the step (unilateral_run.hpp), beside the
/// sticking model's forward Euler. Gaps + separated, − interpenetrating.
void writeUnilateral(const std::string& out) {
  const StickingScene scenes[] = {pivotingBox(), twoFrames()};
  std::ostringstream text;
  text << "# s6_2_unilateral: the hinge gaps of Figs. 6.2 (pivoting_box) and 6.3 (two_frames) at dt 1/60 s: frictionless "
          "unilateral LCP forces (Baraff, epsilon 1e-5, clamp, Gaussian elimination) held over the step by forward or "
          "semi-implicit Euler, no collision handling; and the sticking model's forward Euler\n"
       << "# gap: + separated, - interpenetrating; pivot: the table's edge; hinge: A's edge under B (Fig. 6.3, else 0)\n"
       << "# columns: t_s pivot_gap_m hinge_gap_m penetration_m\n"
       << "# blocks (gnuplot index): pivoting_box unilateral FE, SIE, sticking FE; two_frames the same\n";
  for (const StickingScene& scene : scenes) {
    for (const Integrator integrator : {Integrator::ForwardEuler, Integrator::SemiImplicitEuler}) {
      UnilateralParams params;
      params.integrator = integrator;
      const UnilateralRun run = runUnilateral(scene, kDt, stepsOf(scene, kDt), params);
      text << "# " << scene.name << ", unilateral, " << integratorName(integrator) << "\n";
      for (const UnilateralSample& s : run.samples)
        text << num(s.t) << " " << num(-s.hingeDepth[0]) << " " << num(s.hingeDepth.size() > 1 ? -s.hingeDepth[1] : 0.0)
             << " " << num(s.penetration) << "\n";
      text << "\n\n";
    }
    const StickingRun sticking = runSticking(scene, StickingMethod::ForwardEuler, kDt, stepsOf(scene, kDt));
    text << "# " << scene.name << ", sticking, forward_euler\n";
    for (const StickingSample& s : sticking.samples)
      text << num(s.t) << " " << num(s.contactGap[scene.pivots[0]]) << " "
           << num(scene.pivots.size() > 1 ? s.contactGap[scene.pivots[1]] : 0.0) << " " << num(s.penetration) << "\n";
    text << "\n\n";
  }
  writeFileAtomically(out + "/s6_2_unilateral.dat", text.str());

  // Against dt, forward Euler: Fig. 6.2's largest pivot gap and overlap, Fig. 6.3's deepest
  // pivot overlap and largest hinge gap.
  std::vector<double> series[4];
  for (const double dt : kSweep) {
    double boxGap = 0.0, boxOverlap = 0.0, pivotOverlap = 0.0, hingeGap = 0.0;
    for (const UnilateralSample& s : runUnilateral(scenes[0], dt, stepsOf(scenes[0], dt)).samples) {
      boxGap = std::max(boxGap, -s.hingeDepth[0]);
      boxOverlap = std::max(boxOverlap, s.penetration);
    }
    for (const UnilateralSample& s : runUnilateral(scenes[1], dt, stepsOf(scenes[1], dt)).samples) {
      pivotOverlap = std::max(pivotOverlap, s.hingeDepth[0]);
      hingeGap = std::max(hingeGap, -s.hingeDepth[1]);
    }
    series[0].push_back(boxGap);
    series[1].push_back(boxOverlap);
    series[2].push_back(pivotOverlap);
    series[3].push_back(hingeGap);
  }
  std::ostringstream sweep;
  sweep << "# s6_2_unilateral_vs_dt: frictionless unilateral LCP forces under forward Euler, the extremes over each "
           "scene's window against dt\n"
        << "# slopes (least squares, log-log): fig6_2_pivot_gap " << num(convergenceOrder(kSweep, series[0]))
        << ", fig6_2_overlap " << num(convergenceOrder(kSweep, series[1])) << ", fig6_3_pivot_overlap "
        << num(convergenceOrder(kSweep, series[2])) << ", fig6_3_hinge_gap " << num(convergenceOrder(kSweep, series[3]))
        << "\n# columns: dt_s fig6_2_pivot_gap_m fig6_2_overlap_m fig6_3_pivot_overlap_m fig6_3_hinge_gap_m\n";
  for (std::size_t k = 0; k < kSweep.size(); ++k)
    sweep << num(kSweep[k]) << " " << num(series[0][k]) << " " << num(series[1][k]) << " " << num(series[2][k]) << " "
          << num(series[3][k]) << "\n";
  writeFileAtomically(out + "/s6_2_unilateral_vs_dt.dat", sweep.str());
}

int main(int argc, char** argv) {
  CLI::App app{"Data and frames of the exterior rotation chapter's figures"};
  std::string out = ".";
  bool skipTiming = false;
  app.add_option("--out", out, "Folder the .dat files and images are written to")->capture_default_str();
  app.add_flag("--skip-timing", skipTiming, "Do not measure s6_2_cost (about 2 s)");
  CLI11_PARSE(app, argc, argv);
  try {
    writePenetrationVsTime(out, pivotingGroup(), "fig6_1_penetration_vs_time");
    writePenetrationVsTime(out, pivotingBox(), "fig6_2_penetration_vs_time");
    writePenetrationVsTime(out, twoFrames(), "fig6_3_penetration_vs_time");
    writeSweep(out);
    writeTopBoxPath(out);
    writeUnilateral(out);
    if (!skipTiming) writeCost(out);
    renderStrips(out);
  } catch (const std::exception& e) {
    std::cerr << "exterior_rotation_figures: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
