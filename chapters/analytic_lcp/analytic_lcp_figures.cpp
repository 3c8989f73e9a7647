// Reproduction driver of the analytic contact forces chapter (thesis §2.6.1, §3.3.1, §4.3).
//
// Writes the data of the chapter's figures into the output folder, each file whole or not at
// all: collision events of the dropped die per frame under the analytic method with and
// without sticky collisions and under the basic colliding technique (§4.3); the load each
// level of a resting tower carries under its LCP forces; and the LCP solve time against the
// number of contacts for each linear solver; and §3.3.1's ε swept against every linear solver on
// the contact LCPs of towers, pyramids and uneven stacks. Timings are measurements of this machine.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "boxsim/analytic_lcp/analytic_stepper.hpp"
#include "boxsim/analytic_lcp/contact_matrix.hpp"
#include "boxsim/basic_colliding/basic_colliding.hpp"
#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/geometric_stability/geometric_stability.hpp"
#include "boxsim/io/atomic_file.hpp"
#include "boxsim/io/recorder.hpp"
#include "boxsim/io/render.hpp"
#include "boxsim/io/scene.hpp"
#include "boxsim/io/scene_builders.hpp"

namespace {

using namespace boxsim;

constexpr double kDt = 1.0 / 60.0;

/// ms per call of `work`, repeated for at least 0.1 s so the clock's resolution does not
/// matter.
template <typename Work>
double msPerCall(Work work) {
  const auto start = std::chrono::steady_clock::now();
  int repetitions = 0;
  double elapsed = 0.0;
  do {
    work();
    ++repetitions;
    elapsed = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  } while (elapsed < 100.0);
  return elapsed / repetitions;
}

/// Collision events and kinetic energy of every frame of the die under one stepper.
struct DieRun {
  std::vector<int> events;
  std::vector<double> kinetic;
};

DieRun runDie(const std::string& sceneDir, Stepper& stepper, double duration) {
  World world = loadScene(sceneDir + "/die.json").world;
  DieRun run;
  const long steps = std::lround(duration / kDt);
  for (long k = 0; k < steps; ++k) {
    run.events.push_back(stepper.step(world, kDt).events);
    run.kinetic.push_back(world.kineticEnergy());
  }
  return run;
}

void writeStickyCollisions(const std::string& sceneDir, const std::string& out) {
  // The analytic method as shipped (with its drift correction) and in the thesis' regime
  // (drift correction off: Baraff's LCP asks resting contacts for a >= 0 only), each with and
  // without sticky collisions.
  AnalyticParams sticky, plain, thesisSticky, thesisPlain;
  plain.sticky = false;
  thesisSticky.driftCorrection = false;
  thesisPlain.driftCorrection = false;
  thesisPlain.sticky = false;
  AnalyticStepper stickyStepper(sticky), plainStepper(plain);
  AnalyticStepper thesisStickyStepper(thesisSticky), thesisPlainStepper(thesisPlain);
  BasicCollidingStepper basic;
  const double duration = 10.0;
  const DieRun a = runDie(sceneDir, stickyStepper, duration);
  const DieRun b = runDie(sceneDir, plainStepper, duration);
  const DieRun c = runDie(sceneDir, basic, duration);
  const DieRun d = runDie(sceneDir, thesisStickyStepper, duration);
  const DieRun e = runDie(sceneDir, thesisPlainStepper, duration);
  std::ostringstream text;
  text << "# s4_3_sticky_collisions: the die of chapters/impulse_damped/scenes/die.json, dt 1/60 s\n"
       << "# sticky_speed_m_per_s: " << sticky.stickySpeed << "\n"
       << "# columns: t events_analytic_sticky kinetic_analytic_sticky events_analytic_plain "
          "kinetic_analytic_plain events_basic_colliding kinetic_basic_colliding "
          "events_thesis_sticky kinetic_thesis_sticky events_thesis_plain kinetic_thesis_plain\n";
  for (std::size_t k = 0; k < a.events.size(); ++k) {
    char line[320];
    std::snprintf(line, sizeof line, "%.6f %d %.6e %d %.6e %d %.6e %d %.6e %d %.6e\n", (k + 1) * kDt,
                  a.events[k], a.kinetic[k], b.events[k], b.kinetic[k], c.events[k], c.kinetic[k],
                  d.events[k], d.kinetic[k], e.events[k], e.kinetic[k]);
    text << line;
  }
  writeFileAtomically(out + "/s4_3_sticky_collisions.dat", text.str());
}

/// A resting tower of `boxes` unit cubes on the ground, and the contact LCP (A, b) of the
/// contacts closer than `margin` m.
World restingTower(int boxes, double margin, std::vector<PointContact>& contacts, MatX& A, VecX& b) {
  World world;
  world.addGround(0.0, 50.0);
  addTower(world, TowerSpec{boxes});
  contacts = pointContacts(world, findContacts(world, margin));
  contactMatrix(world, contacts, A, b);
  return world;
}

void writeTowerForces(const std::string& out) {
  const int count = 10;
  std::vector<PointContact> contacts;
  MatX A;
  VecX b;
  const World world = restingTower(count, 1e-6, contacts, A, b);
  const LcpResult r = solveContactLcp(A, b);
  std::vector<double> load(world.bodies.size(), 0.0);
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const PointContact& c = contacts[i];
    const int upper = world.bodies[c.a].s.x.y() > world.bodies[c.b].s.x.y() ? c.a : c.b;
    load[upper] += r.f[static_cast<int>(i)] * std::abs(c.normal.y());
  }
  std::ostringstream text;
  text << "# s2_6_tower_forces: a resting tower of " << count
       << " unit cubes of 1 kg, LCP forces (epsilon 1e-5)\n"
       << "# columns: level load_N expected_N\n";
  for (int k = 1; k <= count; ++k)
    text << k << " " << load[k] << " " << (count - k + 1) * -world.gravity.y() << "\n";
  writeFileAtomically(out + "/s2_6_tower_forces.dat", text.str());
}

void writeSolveTimes(const std::string& out) {
  std::ostringstream text;
  text << "# s3_3_lcp_solve_time: resting towers of unit cubes, one thread, this machine\n"
       << "# columns: contacts ms_incremental_cholesky ms_ldlt ms_complete_orthogonal\n";
  for (int boxes : {1, 2, 4, 8, 16, 32, 64}) {
    std::vector<PointContact> contacts;
    MatX A;
    VecX b;
    restingTower(boxes, 1e-3, contacts, A, b);
    text << contacts.size();
    for (const LcpLinearSolver solver : {LcpLinearSolver::IncrementalCholesky, LcpLinearSolver::Ldlt,
                                         LcpLinearSolver::CompleteOrthogonal}) {
      LcpParams params;
      params.linearSolver = solver;
      text << " " << msPerCall([&] { solveContactLcp(A, b, params); });
    }
    text << "\n";
  }
  writeFileAtomically(out + "/s3_3_lcp_solve_time.dat", text.str());
}

/// A stack of `count` boxes of uneven sizes on the ground, each turned about y and set off the
/// centre of the one below by up to 0.6 of its half width, touching: the random stacks of the ε
/// sweep. The numbers are fractional parts of multiples of irrational constants (a Weyl
/// sequence from `seed`), the same on every machine. Some stacks stand, some topple.
World unevenStack(int seed, int count) {
  World world;
  world.addGround(0.0, 50.0);
  double k = 7.0 * seed;
  const auto next = [&k] {
    k += 1.0;
    return k * 0.6180339887498949 - std::floor(k * 0.6180339887498949);
  };
  double top = 0.0, below = 0.5;
  Vec3 centre = Vec3::Zero();
  for (int i = 0; i < count; ++i) {
    const Vec3 half(0.25 + 0.35 * next(), 0.25 + 0.35 * next(), 0.25 + 0.35 * next());
    RigidBody box = RigidBody::box(half, 8.0 * half.prod());
    if (i > 0) centre += Vec3((next() - 0.5) * 1.2 * below, 0.0, (next() - 0.5) * 1.2 * below);
    box.s.x = Vec3(centre.x(), top + half.y(), centre.z());
    box.s.q = Quat(Eigen::AngleAxisd(2.0 * kPi * next(), Vec3::UnitY()));
    box.updateDerived();
    world.add(box, "box" + std::to_string(i));
    top += 2.0 * half.y();
    below = std::min(half.x(), half.z());
  }
  return world;
}

/// One contact LCP of the ε sweep and the scene family it came from.
struct SweepProblem {
  MatX A;
  VecX b;
  int family = 0;  ///< 0 towers, 1 pyramids, 2 uneven stacks
};

/// The contact LCPs (contacts closer than 1 mm) of every fifth step of 1 s of `world` under
/// the analytic method.
void collectProblems(World world, int family, std::vector<SweepProblem>& problems) {
  AnalyticStepper stepper;
  for (int k = 0; k < 60; ++k) {
    if (k % 5 == 0) {
      const std::vector<PointContact> contacts = pointContacts(world, findContacts(world, 1e-3));
      if (!contacts.empty()) {
        SweepProblem p;
        contactMatrix(world, contacts, p.A, p.b);
        p.family = family;
        problems.push_back(std::move(p));
      }
    }
    stepper.step(world, kDt);
  }
}

/// §3.3.1's ε, swept: ε ∈ {0, 1e-8, 1e-5} m/s² × every linear solver × snapping to the bounds
/// on and off, on the contact LCPs of resting towers (2, 5, 10 cubes), touching pyramids (base
/// 3 and 5) and 20 uneven stacks along 1 s of the analytic method. Per setting: solves that hit
/// the pivot guard (cycling), per family; pivots; the worst scaled LCP violation of the forces
/// returned, converged or not.
void writeEpsilonSweep(const std::string& out) {
  std::vector<SweepProblem> problems;
  for (int count : {2, 5, 10}) {
    World world;
    world.addGround(0.0, 50.0);
    addTower(world, TowerSpec{count});
    collectProblems(world, 0, problems);
  }
  for (int base : {3, 5}) {
    World world;
    world.addGround(0.0, 50.0);
    PyramidSpec spec;
    spec.base = base;
    addPyramid(world, spec);
    collectProblems(world, 1, problems);
  }
  for (int seed = 1; seed <= 20; ++seed) collectProblems(unevenStack(seed, 2 + seed % 6), 2, problems);
  int perFamily[3] = {0, 0, 0};
  for (const SweepProblem& p : problems) ++perFamily[p.family];
  std::ostringstream text;
  text << "# s3_3_epsilon_sweep: " << problems.size() << " contact LCPs (towers " << perFamily[0]
       << ", pyramids " << perFamily[1] << ", uneven stacks " << perFamily[2]
       << "), pivot guard " << LcpParams{}.maxPivotsPerContact << " n\n"
       << "# solver: 0 incremental_cholesky, 1 ldlt, 2 complete_orthogonal, 3 gaussian_elimination\n"
       << "# columns: epsilon snap solver cycled_towers cycled_pyramids cycled_stacks cycled_percent "
          "mean_pivots worst_violation\n";
  const LcpLinearSolver solvers[] = {LcpLinearSolver::IncrementalCholesky, LcpLinearSolver::Ldlt,
                                     LcpLinearSolver::CompleteOrthogonal,
                                     LcpLinearSolver::GaussianElimination};
  for (const double epsilon : {0.0, 1e-8, 1e-5})
    for (const bool snap : {false, true})
      for (int s = 0; s < 4; ++s) {
        LcpParams params;
        params.epsilon = epsilon;
        params.snapToBounds = snap;
        params.linearSolver = solvers[s];
        int cycled[3] = {0, 0, 0};
        long pivots = 0;
        double worst = 0.0;
        for (const SweepProblem& p : problems) {
          const LcpResult r = solveContactLcp(p.A, p.b, params);
          cycled[p.family] += r.converged ? 0 : 1;
          pivots += r.pivots;
          worst = std::max(worst, lcpViolation(p.A, p.b, r.f));
        }
        char line[200];
        std::snprintf(line, sizeof line, "%g %d %d %d %d %d %.3f %.2f %.3e\n", epsilon, int(snap), s,
                      cycled[0], cycled[1], cycled[2],
                      100.0 * (cycled[0] + cycled[1] + cycled[2]) / double(problems.size()),
                      double(pivots) / double(problems.size()), worst);
        text << line;
      }
  writeFileAtomically(out + "/s3_3_epsilon_sweep.dat", text.str());
}

/// The deepest overlap (m) of any pair closer than 1 mm, 0 when none overlaps.
double deepestOverlap(const World& world) {
  double deepest = 0.0;
  for (const ContactManifold& m : findContacts(world, 1e-3))
    for (int k = 0; k < m.count; ++k) deepest = std::max(deepest, m.points[k].depth);
  return deepest;
}

/// §3.3.1's no-clamp failure, measured: a resting tower of 10 under the thesis' own LCP
/// settings (Gaussian elimination, Baraff's drive_to_zero as printed, no drift correction) with
/// and without the force clamp, and under the defaults (clamp and drift correction on). Per
/// frame and run: the most negative LCP force before the clamp and the deepest overlap.
void writeNoClamp(const std::string& out) {
  // 15 s: the drift reaches the collision loop's depth tolerance (1e-4 m) near 17 s, after
  // which every step bisects for a collision.
  const double duration = 15.0;
  const long steps = std::lround(duration / kDt);
  std::vector<std::vector<double>> columns;
  for (const int run : {0, 1, 2}) {
    World world;
    world.addGround(0.0, 50.0);
    addTower(world, TowerSpec{10});
    AnalyticParams params;
    if (run < 2) {
      params.lcp.linearSolver = LcpLinearSolver::GaussianElimination;
      params.lcp.snapToBounds = false;
      params.lcp.clampNegativeForces = run == 0;
      params.driftCorrection = false;
    }
    AnalyticStepper stepper(params);
    std::vector<double> force, overlap;
    for (long k = 0; k < steps; ++k) {
      stepper.step(world, kDt);
      force.push_back(stepper.lastMostNegativeForce());
      overlap.push_back(deepestOverlap(world));
    }
    columns.push_back(force);
    columns.push_back(overlap);
  }
  std::ostringstream text;
  text << "# s3_3_no_clamp: resting tower of 10 unit cubes, dt 1/60 s, epsilon 1e-5\n"
       << "# runs: thesis_clamp and thesis_noclamp (gaussian_elimination, snap_to_bounds off, "
          "drift_correction off), defaults (incremental_cholesky, clamp, drift_correction on)\n"
       << "# columns: t, then per run: most_negative_force_N deepest_overlap_m\n";
  for (long k = 0; k < steps; ++k) {
    char line[64];
    std::snprintf(line, sizeof line, "%.6f", (k + 1) * kDt);
    text << line;
    for (const std::vector<double>& c : columns) {
      std::snprintf(line, sizeof line, " %.6e", c[k]);
      text << line;
    }
    text << "\n";
  }
  writeFileAtomically(out + "/s3_3_no_clamp.dat", text.str());
}

/// Fig. 5.6's scene: a one-box-deep pyramid of the given base with 5 cm gaps in its rows and
/// its bottom centre box left out, on the ground.
World fig5_6Pyramid(int base) {
  World world;
  world.addGround(0.0, 50.0);
  addPyramid(world, PyramidSpec{base, 1.0, 1.0, Vec3::Zero(), 0.05}, {{0, base / 2}});
  return world;
}

/// Figs. 5.3–5.6 in 3D: each configuration classified (§5.4) and drawn with its stable
/// bodies dark grey and the others light grey, as the thesis colours Fig. 5.6.
void renderStabilityFigures(const std::string& out) {
  const auto withGround = [](auto add) {
    World world;
    world.addGround(0.0, 50.0);
    add(world);
    return world;
  };
  struct Figure {
    std::string stem, title;
    World world;
  };
  const std::vector<Figure> figures = {
      {"fig5_3_one_corner_over", "Fig. 5.3: one corner over the box below - not stable",
       withGround([](World& w) { addOneCornerOver(w); })},
      {"fig5_4_on_wider_box", "Fig. 5.4: on a stable box - stable",
       withGround([](World& w) { addBoxOnWiderBox(w); })},
      {"fig5_5_bridge", "Fig. 5.5: on two stable boxes - stable",
       withGround([](World& w) { addBridge(w); })},
      {"fig5_6_pyramid_3d", "Fig. 5.6: bottom centre removed (dark: stable)", fig5_6Pyramid(9)}};
  for (const auto& [stem, title, world] : figures) {
    const std::vector<char> stable = setGeometricallyStable(world, findContacts(world, 1e-6));
    Recorder recorder(world, {{"scene", stem}});
    recorder.capture(world, 0.0);
    RenderOptions options;
    options.width = 640;
    options.height = 480;
    options.title = title;
    for (std::size_t k = 0; k < world.bodies.size(); ++k)
      if (!world.bodies[k].immovable)
        options.bodyColours[world.names[k]] = stable[k] ? 0x666666 : 0xd9d9d9;
    renderTrajectory(recorder.trajectory(), out + "/" + stem + ".png", options);
  }
}

/// Fig. 5.3's right panel, the contact plane seen from above (x and z, m): the outlines of the
/// lower cube's top face and the upper cube's bottom face, the contact points between them, and
/// the upper cube's centre of mass. Blocks for gnuplot's `index`: 0 lower outline, 1 upper
/// outline, 2 the contact points as a closed polygon, 3 the centre of mass.
void writeFig5_3ContactPlane(const std::string& out) {
  World world;
  world.addGround(0.0, 50.0);
  addOneCornerOver(world);
  const int lower = 1, upper = 2;  // addOneCornerOver adds "lower", then "upper", after the ground
  const auto outline = [&world](int k, double ySign) {
    const RigidBody& body = world.bodies[static_cast<std::size_t>(k)];
    const Vec3 h = body.halfExtents;
    std::ostringstream block;
    for (const auto& [sx, sz] : {std::pair(-1, -1), {1, -1}, {1, 1}, {-1, 1}, {-1, -1}}) {
      const Vec3 corner = body.s.x + body.R * Vec3(sx * h.x(), ySign * h.y(), sz * h.z());
      block << corner.x() << " " << corner.z() << "\n";
    }
    return block.str();
  };
  std::vector<Vec3> points;
  for (const ContactManifold& m : findContacts(world, 1e-6))
    if ((m.a == lower && m.b == upper) || (m.a == upper && m.b == lower))
      for (int i = 0; i < m.count; ++i) points.push_back(m.points[static_cast<std::size_t>(i)].position);
  if (points.empty()) throw std::runtime_error("fig5_3: the upper cube does not touch the lower one");
  Vec3 mean = Vec3::Zero();
  for (const Vec3& p : points) mean += p / double(points.size());
  std::sort(points.begin(), points.end(), [&mean](const Vec3& p, const Vec3& q) {
    return std::atan2(p.z() - mean.z(), p.x() - mean.x()) < std::atan2(q.z() - mean.z(), q.x() - mean.x());
  });
  points.push_back(points.front());
  const Vec3 com = world.bodies[upper].s.x;
  std::ostringstream text;
  text << "# fig5_3_contact_plane: thesis Fig. 5.3, right, seen from above; columns: x_m z_m\n"
       << "# contact_points: " << points.size() - 1 << "\n"
       << "# lower cube, top face\n" << outline(lower, 1.0) << "\n\n"
       << "# upper cube, bottom face\n" << outline(upper, -1.0) << "\n\n"
       << "# contact points (closed)\n";
  for (const Vec3& p : points) text << p.x() << " " << p.z() << "\n";
  text << "\n\n# upper cube, centre of mass\n" << com.x() << " " << com.z() << "\n";
  writeFileAtomically(out + "/fig5_3_contact_plane.dat", text.str());
}

/// Fig. 5.6: a one-box-deep pyramid of base 9 with 5 cm gaps in its rows (side contacts would
/// make every box unstable, normals off the y axis) and its bottom centre box removed. One row
/// per box: its centre and half size in the side view, whether it is geometrically stable, and
/// in the header the LCP size and solve time without and with the §5.4 exclusion.
void writePyramidStability(const std::string& out) {
  const int base = 9;
  const World world = fig5_6Pyramid(base);
  const std::vector<char> stable = setGeometricallyStable(world, findContacts(world, 1e-6));
  std::ostringstream text;
  text << "# fig5_6_pyramid_stability: pyramid of base " << base
       << ", gaps 0.05 m, bottom centre box removed; side view\n";
  for (const bool exclusion : {false, true}) {
    AnalyticParams params;
    params.useGeometricStability = exclusion;
    const AnalyticStepper stepper(params);
    const double ms = msPerCall([&] { stepper.contactWrenches(world, kDt); });
    char line[160];
    std::snprintf(line, sizeof line, "# %s: %d contacts, %.2f ms\n",
                  exclusion ? "with_exclusion" : "full_lcp", stepper.lastLcpSize(),
                  ms);
    text << line;
  }
  text << "# columns: x y half_x half_y stable\n";
  for (std::size_t k = 0; k < world.bodies.size(); ++k) {
    const RigidBody& b = world.bodies[k];
    if (b.immovable) continue;
    text << b.s.x.x() << " " << b.s.x.y() << " " << b.halfExtents.x() << " " << b.halfExtents.y()
         << " " << int(stable[k]) << "\n";
  }
  writeFileAtomically(out + "/fig5_6_pyramid_stability.dat", text.str());
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Data of the analytic contact forces chapter's figures"};
  std::string sceneDir = "chapters/impulse_damped/scenes";
  std::string out = ".";
  app.add_option("--scenes", sceneDir, "Folder of the scenes (die.json)")->capture_default_str();
  app.add_option("--out", out, "Folder the .dat files are written to")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  try {
    writeStickyCollisions(sceneDir, out);
    writeTowerForces(out);
    writeSolveTimes(out);
    writeNoClamp(out);
    writeEpsilonSweep(out);
    writePyramidStability(out);
    renderStabilityFigures(out);
    writeFig5_3ContactPlane(out);
  } catch (const std::exception& e) {
    std::cerr << "analytic_lcp_figures: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
