// The impulse chapter's friction figures (friction_figures.hpp): Fig. 5.2 and Coulomb friction
// on an incline, under the plain impulse step and damped integration. Writes data only, each
// file whole or not at all.
#include "friction_figures.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "boxsim/impulse_damped/damped_integration.hpp"
#include "boxsim/impulse_damped/impulse_stepper.hpp"
#include "boxsim/io/atomic_file.hpp"
#include "boxsim/io/scene_builders.hpp"
#include "figure_data.hpp"

namespace boxsim {

/// Fig. 5.2: damping against Newtonian friction along a chain. Box A (a 1 kg unit cube) slides
/// at 2 m/s on box B (1 kg, 3 m × 0.5 m × 2 m), which rests on frictionless ground. Under damped
/// integration as the thesis has it (frictionless, damping standing in for friction) A slows and
/// B never moves; under Coulomb friction (μ = 0.5 between A and B, closed form) the force that
/// slows A drags B along (force B of the caption), until both move at the common velocity
/// m_A v0 / (m_A + m_B) that momentum conservation gives.
void figFig5_2DampingVsFriction(const std::string& dir) {
  const double v0 = 2.0, mu = 0.5, g = 9.81, mA = 1.0, mB = 1.0;
  World world;
  world.addGround(0.0, 50.0);
  const int b = addBox(world, "B", Vec3(1.5, 0.25, 1.0), Vec3(0.0, 0.25, 0.0));
  const int a = addBox(world, "A", Vec3(0.5, 0.5, 0.5), Vec3(-0.9, 1.0, 0.0));
  world.bodies[static_cast<std::size_t>(a)].setVelocity(Vec3(v0, 0.0, 0.0));
  DampedIntegrationStepper stepper;
  std::string out = header("fig5_2_damping_vs_friction: A (1 kg cube) slides at 2 m/s on B (1 kg), "
                           "B on frictionless ground; Coulomb: mu 0.5 between A and B, closed form",
                           "t_s vA_damped vB_damped vA_coulomb vB_coulomb");
  const double common = mA * v0 / (mA + mB);
  for (int k = 0; k <= 90; ++k) {
    const double t = k / 60.0;
    if (k > 0) stepper.step(world, 1.0 / 60.0);
    // Coulomb: A decelerates at mu g, B accelerates at mu g mA / mB, until they move together.
    const double vA = std::max(common, v0 - mu * g * t);
    const double vB = std::min(common, mu * g * mA / mB * t);
    char line[200];
    std::snprintf(line, sizeof line, "%.6f %.6g %.6g %.6g %.6g\n", t,
                  world.bodies[static_cast<std::size_t>(a)].v.x(),
                  world.bodies[static_cast<std::size_t>(b)].v.x(), vA, vB);
    out += line;
  }
  writeFileAtomically(dir + "/fig5_2_damping_vs_friction.dat", out);
}

/// Beyond the thesis: a frictional cube (μ = 0.5) released on inclines of 20°-45°, its distance
/// down the slope against time under the plain impulse step, damped integration with its
/// damping and sleeping off, and damped integration as the thesis has it; beside Coulomb's
/// a = g (sin θ − μ cos θ), stepped as semi-implicit Euler does: s_k = a Δt² k (k + 1) / 2.
void figS7FrictionIncline(const std::string& dir) {
  const double mu = 0.5, dt = 1.0 / 60.0;
  const int steps = 120;
  const std::vector<double> angles = {20.0, 25.0, 30.0, 35.0, 45.0};
  const auto stepperOf = [](int kind) -> std::unique_ptr<Stepper> {
    if (kind == 0) return std::make_unique<ImpulseStepper>();
    DampedIntegrationParams p;
    if (kind == 1) {
      p.damp = false;
      p.sleep.enabled = false;
    }
    return std::make_unique<DampedIntegrationStepper>(p);
  };
  std::string columns = "t_s";
  for (double degrees : angles)
    for (const char* what : {"coulomb", "impulse", "damped_undamped", "damped"})
      columns.append(" ").append(what).append("_")
          .append(std::to_string(static_cast<int>(degrees))).append("deg_m");
  // distance[angle][kind][step]
  std::vector<std::vector<std::vector<double>>> distance(angles.size(), std::vector<std::vector<double>>(3));
  for (std::size_t i = 0; i < angles.size(); ++i)
    for (int kind = 0; kind < 3; ++kind) {
      World world;
      world.restitution = 0.0;
      Vec3 down;
      const int box = addIncline(world, angles[i], {mu, mu}, &down);
      const Vec3 start = world.bodies[box].s.x;
      const std::unique_ptr<Stepper> stepper = stepperOf(kind);
      distance[i][kind].push_back(0.0);
      for (int k = 1; k <= steps; ++k) {
        stepper->step(world, dt);
        distance[i][kind].push_back((world.bodies[box].s.x - start).dot(down));
      }
    }
  std::string out = header("s7_friction_incline: a cube with mu = 0.5 released on inclines, distance down the "
                           "slope (Coulomb: a = g (sin - mu cos), 0 below atan mu = 26.6 deg)", columns);
  for (int k = 0; k <= steps; ++k) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.6f", k * dt);
    out += buffer;
    for (std::size_t i = 0; i < angles.size(); ++i) {
      const double theta = angles[i] * kPi / 180.0;
      const double a = std::max(0.0, 9.81 * (std::sin(theta) - mu * std::cos(theta)));
      std::snprintf(buffer, sizeof buffer, " %.6e", a * dt * dt * k * (k + 1) / 2.0);
      out += buffer;
      for (int kind = 0; kind < 3; ++kind) {
        std::snprintf(buffer, sizeof buffer, " %.6e", distance[i][kind][k]);
        out += buffer;
      }
    }
    out += "\n";
  }
  writeFileAtomically(dir + "/s7_friction_incline.dat", out);
}

/// Beyond the thesis, the classic incline test: a frictional cube (μ = 0.5) released on inclines
/// of 0°-60° (every 2.5°), its distance down the slope after 2 s under the plain impulse step and
/// under damped integration as it runs by default (damping and sleeping on), beside Coulomb's
/// a = g (sin θ − μ cos θ) stepped as semi-implicit Euler does (0 below atan μ = 26.6°); and the
/// same cube frictionless (μ = 0) under damped integration, where the thesis' damping stands in
/// for friction (§5.3), beside the frictionless law a = g sin θ stepped the same way.
void figS7FrictionInclineSweep(const std::string& dir) {
  const double mu = 0.5, dt = 1.0 / 60.0;
  const int steps = 120;
  std::string out = header("s7_friction_incline_sweep: a cube with mu = 0.5 released on an incline, distance "
                           "down the slope after 2 s against the incline's angle",
                           "angle_deg coulomb_m impulse_m damped_m frictionless_m damped_frictionless_m");
  for (int tenth = 0; tenth <= 600; tenth += 25) {
    const double degrees = tenth / 10.0;
    const double theta = degrees * kPi / 180.0;
    const double a = std::max(0.0, 9.81 * (std::sin(theta) - mu * std::cos(theta)));
    char buffer[96];
    const double stepped = dt * dt * steps * (steps + 1) / 2.0;  // s / a after the steps
    std::snprintf(buffer, sizeof buffer, "%.1f %.6e", degrees, a * stepped);
    out += buffer;
    // The plain impulse step and damped integration with μ = 0.5, then damped integration
    // with μ = 0, after the frictionless law.
    for (int kind = 0; kind < 3; ++kind) {
      World world;
      world.restitution = 0.0;
      Vec3 down;
      const double coefficient = kind < 2 ? mu : 0.0;
      const int box = addIncline(world, degrees, {coefficient, coefficient}, &down);
      const Vec3 start = world.bodies[box].s.x;
      std::unique_ptr<Stepper> stepper;
      if (kind == 0)
        stepper = std::make_unique<ImpulseStepper>();
      else
        stepper = std::make_unique<DampedIntegrationStepper>();
      for (int k = 1; k <= steps; ++k) stepper->step(world, dt);
      if (kind == 2) {
        std::snprintf(buffer, sizeof buffer, " %.6e", 9.81 * std::sin(theta) * stepped);
        out += buffer;
      }
      std::snprintf(buffer, sizeof buffer, " %.6e", (world.bodies[box].s.x - start).dot(down));
      out += buffer;
    }
    out += "\n";
  }
  writeFileAtomically(dir + "/s7_friction_incline_sweep.dat", out);
}

}  // namespace boxsim
