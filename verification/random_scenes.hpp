// Random scenes for the stress tests (verification/stress_test.cpp) and the long stress run
// (bench/stress_bench.cpp), and the invariants both check on every step of every technique.
//
// A scene is a pure function of its seed: the numbers come from SeededRandom (GSL's mt19937
// and GSL's own mapping to [0, 1), fixed by GSL rather than by the C++ standard library), drawn
// in a fixed order, so a failing seed printed by the long run rebuilds the same scene anywhere.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "boxsim/collision/obb.hpp"
#include "boxsim/core/stepper.hpp"
#include "boxsim/impulse_damped/fix_contact_constraints.hpp"
#include "boxsim/impulse_damped/impulse_params.hpp"
#include "seeded_random.hpp"
#include "test_worlds.hpp"

namespace boxsim::testing {

/// The three arrangements a random scene can take.
enum class SceneKind {
  Scatter,  ///< boxes apart in the air, thrown at up to the largest speed and spin
  Pile,     ///< columns of boxes stacked face on face, each touching the one below, on the ground
  Resting,  ///< boxes lying on the ground on a face, side by side, neighbours touching
};

/// "scatter", "pile" or "resting".
inline const char* sceneKindName(SceneKind kind) {
  switch (kind) {
    case SceneKind::Scatter: return "scatter";
    case SceneKind::Pile: return "pile";
    case SceneKind::Resting: return "resting";
  }
  return "unknown";
}

/// Ranges a random scene is drawn from.
struct RandomSceneSpec {
  int minBodies = 2;             ///< fewest movable boxes
  int maxBodies = 6;             ///< most movable boxes
  double minHalfExtent = 0.05;   ///< m: each half extent is log-uniform in [min, max]
  double maxHalfExtent = 5.0;    ///< m
  double minMass = 1.0;          ///< kg: masses are log-uniform in [minMass, maxMassRatio minMass]
  double maxMassRatio = 1000.0;  ///< heaviest over lightest body a scene can hold
  double maxSpeed = 50.0;        ///< m/s: centre speeds of thrown boxes are uniform in [0, max]
  /// rad/s: spins are uniform in [0, min(maxSpin, maxSpeed / ρ)] (ρ the box's half diagonal),
  /// so no vertex is thrown faster than maxSpeed by the spin alone.
  double maxSpin = 30.0;
  /// The time steps a scene may take, one chosen uniformly: 1e-4 s (tiny), 1/60 s (the thesis'
  /// frame), 1/15 s and 1/10 s (large: a 50 m/s box then jumps 3.3 m and 5 m per step).
  std::vector<double> dts = {1e-4, 1.0 / 60.0, 1.0 / 15.0, 1.0 / 10.0};
  /// Steps to run: the scene's dt is taken this many times, or fewer when maxDuration says so.
  int steps = 60;
  /// s: the most simulated time per scene (so a large dt does not run for long).
  double maxDuration = 2.0;
};

/// m: half the thickness of the random scenes' ground. A box thrown down at 50 m/s, plus what
/// gravity adds in the 2 s a scene lasts (70 m/s in all), moves 7 m in a step of 1/10 s: through
/// the 1 m slab of groundWorld(), unseen. Such tunnelling is the known limit of every technique
/// but the swept timewarp (chapters/timewarp/README.md, "Tunnelling"), not what the stress
/// checks look for; under a 20 m slab, a box found under the ground is one the technique failed
/// to push back out.
inline constexpr double kGroundHalfThickness = 10.0;

/// A random scene with its time step, ready to run.
struct RandomScene {
  World world;              ///< the ground (top face y = 0, 100 m square, 20 m thick) and the boxes
  double dt = 1.0 / 60.0;   ///< s
  int steps = 0;            ///< steps to take
  unsigned long seed = 0;   ///< the seed it was drawn from
  SceneKind kind = SceneKind::Scatter;  ///< its arrangement
  /// One line: seed, kind, body count, dt, steps (for failure messages).
  std::string describe() const {
    std::ostringstream out;
    out << "seed " << seed << " (" << sceneKindName(kind) << ", " << world.movableCount()
        << " boxes, dt " << dt << " s, " << steps << " steps)";
    return out.str();
  }
};

namespace detail {

inline double logUniform(SeededRandom& random, double lo, double hi) {
  return std::exp(random.uniform(std::log(lo), std::log(hi)));
}

/// A direction uniform on the unit sphere (Marsaglia's method, by rejection).
inline Vec3 unitVector(SeededRandom& random) {
  for (;;) {
    const Vec3 v = random.vector(-1.0, 1.0);
    const double n2 = v.squaredNorm();
    if (n2 > 1e-6 && n2 <= 1.0) return v / std::sqrt(n2);
  }
}

/// A rotation by a uniform angle about the vertical: keeps a face down and the face up.
inline Quat yaw(SeededRandom& random) {
  return Quat(Eigen::AngleAxisd(random.uniform(0.0, 2.0 * kPi), Vec3::UnitY()));
}

inline Vec3 randomHalfExtents(SeededRandom& random, const RandomSceneSpec& spec) {
  return Vec3(logUniform(random, spec.minHalfExtent, spec.maxHalfExtent),
              logUniform(random, spec.minHalfExtent, spec.maxHalfExtent),
              logUniform(random, spec.minHalfExtent, spec.maxHalfExtent));
}

/// Adds a box at rest and returns its index.
inline int addRandomBox(World& world, SeededRandom& random, const RandomSceneSpec& spec,
                        const Vec3& halfExtents, const Vec3& centre, const Quat& q) {
  RigidBody body = RigidBody::box(halfExtents, logUniform(random, spec.minMass,
                                                          spec.minMass * spec.maxMassRatio));
  body.s.x = centre;
  body.s.q = q;
  body.updateDerived();
  return world.add(body, "box" + std::to_string(world.bodies.size()));
}

/// A velocity of uniform direction and speed in [0, maxSpeed], and a spin as RandomSceneSpec
/// says.
inline void throwBox(RigidBody& body, SeededRandom& random, const RandomSceneSpec& spec) {
  body.setVelocity(random.uniform(0.0, spec.maxSpeed) * unitVector(random));
  const double rho = body.halfExtents.norm();
  body.setAngularVelocity(random.uniform(0.0, std::min(spec.maxSpin, spec.maxSpeed / rho)) *
                          unitVector(random));
}

/// Boxes apart in a region above the ground: bounding spheres never overlap, so the boxes
/// cannot; rejection sampling with a bounded number of tries (a box that finds no room is
/// left out, so a scene may hold fewer than asked, never overlapping ones).
inline void scatter(World& world, SeededRandom& random, const RandomSceneSpec& spec, int count) {
  std::vector<Vec3> centres;
  std::vector<double> radii;
  for (int i = 0; i < count; ++i) {
    const Vec3 h = randomHalfExtents(random, spec);
    const double rho = h.norm();
    for (int attempt = 0; attempt < 50; ++attempt) {
      const Vec3 c(random.uniform(-15.0, 15.0), rho + random.uniform(0.0, 10.0),
                   random.uniform(-15.0, 15.0));
      bool free = true;
      for (std::size_t j = 0; j < centres.size() && free; ++j)
        free = (c - centres[j]).norm() > rho + radii[j];
      if (!free) continue;
      centres.push_back(c);
      radii.push_back(rho);
      const int k = addRandomBox(world, random, spec, h, c, random.rotation());
      throwBox(world.bodies[k], random, spec);
      break;
    }
  }
}

/// Columns of boxes on the ground, each box lying face on face on the one below (turned about
/// the vertical by a random yaw and shifted by up to half of the narrower footprint, so it may
/// topple), the lowest on the ground. Columns stand apart by their footprints' circumradii.
inline void pile(World& world, SeededRandom& random, const RandomSceneSpec& spec, int count) {
  const int columns = random.integer(1, std::max(1, count / 2));
  double nextX = -10.0;
  int placed = 0;
  for (int c = 0; c < columns; ++c) {
    const int height = c + 1 == columns ? count - placed : random.integer(1, count - placed - (columns - c - 1));
    const double z = random.uniform(-5.0, 5.0);
    double base = 0.0;     // top of the box below, m
    double widest = 0.0;   // the column's largest footprint circumradius, m
    Vec3 below = Vec3(nextX, 0.0, z);
    double belowReach = std::numeric_limits<double>::infinity();
    std::vector<int> members;
    for (int k = 0; k < height; ++k) {
      const Vec3 h = randomHalfExtents(random, spec);
      const double reach = std::min(h.x(), h.z());
      const double shift = 0.5 * std::min(reach, belowReach);
      const Vec3 centre(below.x() + random.uniform(-shift, shift), base + h.y(),
                        below.z() + random.uniform(-shift, shift));
      members.push_back(addRandomBox(world, random, spec, h, centre, yaw(random)));
      widest = std::max(widest, std::hypot(h.x(), h.z()) + std::abs(centre.x() - nextX));
      base += 2.0 * h.y();
      below = centre;
      belowReach = reach;
    }
    // The column was built around nextX; move it right by its reach so it clears the last one.
    for (const int m : members) {
      world.bodies[m].s.x.x() += widest;
      world.bodies[m].updateDerived();
    }
    nextX += 2.0 * widest + random.uniform(0.0, 1.0);
    placed += height;
  }
}

/// Boxes lying on the ground on a face, in a row along x; each touches the previous one
/// (faces perpendicular to x, no gap) with probability ½, else stands a gap of up to 1 m off.
/// Each gets a small random velocity (up to 1 m/s) and spin about the vertical.
inline void resting(World& world, SeededRandom& random, const RandomSceneSpec& spec, int count) {
  double x = -10.0;
  for (int i = 0; i < count; ++i) {
    const Vec3 h = randomHalfExtents(random, spec);
    if (i > 0 && random.integer(0, 1) == 1) x += random.uniform(0.0, 1.0);
    const int k = addRandomBox(world, random, spec, h, Vec3(x + h.x(), h.y(), random.uniform(-0.5, 0.5)),
                               Quat::Identity());
    world.bodies[k].setVelocity(Vec3(random.uniform(-1.0, 1.0), 0.0, random.uniform(-1.0, 1.0)));
    world.bodies[k].setAngularVelocity(Vec3(0.0, random.uniform(-1.0, 1.0), 0.0));
    x += 2.0 * h.x();
  }
}

}  // namespace detail

/// The scene of a seed: kind, body count, time step and every box drawn from `spec`. The same
/// seed and spec give the same scene, bit for bit.
inline RandomScene randomScene(unsigned long seed, const RandomSceneSpec& spec = {}) {
  SeededRandom random(seed);
  RandomScene scene;
  scene.seed = seed;
  // The ground of groundWorld(), but kGroundHalfThickness thick (see there).
  scene.world.addGround(0.0, 50.0, kGroundHalfThickness);
  scene.kind = static_cast<SceneKind>(random.integer(0, 2));
  scene.dt = spec.dts[static_cast<std::size_t>(random.integer(0, static_cast<int>(spec.dts.size()) - 1))];
  scene.steps = std::max(1, std::min(spec.steps, static_cast<int>(spec.maxDuration / scene.dt)));
  const int count = random.integer(spec.minBodies, spec.maxBodies);
  switch (scene.kind) {
    case SceneKind::Scatter: detail::scatter(scene.world, random, spec, count); break;
    case SceneKind::Pile: detail::pile(scene.world, random, spec, count); break;
    case SceneKind::Resting: detail::resting(scene.world, random, spec, count); break;
  }
  return scene;
}

/// The contact tolerance a technique documents, m, for a body of smallest half extent ℓ (m):
/// how deep it lets a resting contact sink before it acts. The impulse-based techniques and the
/// timewarp's FIXINTERPENETRATION allow the slop of FixContactParams (1e-3 ℓ); the analytic
/// method's bisection stops at a depth of 1e-4 m (AnalyticParams::loop) and the basic colliding
/// technique's at 1e-9 m. The larger of the two bounds is taken for every technique: the check
/// it enters is about bodies passing through the ground, not about the last tenth of a mm.
inline double contactTolerance(double ell) { return std::max(1e-4, FixContactParams{}.slop * ell); }

/// What runStressChecks found.
struct StressOutcome {
  long steps = 0;             ///< steps taken (fewer than asked when a check failed)
  long limitedSteps = 0;      ///< steps that hit the technique's work limit
  std::string failure;        ///< empty when every check held; else what failed, when, which body
  double deepestBelowGround = 0.0;  ///< m: the largest depth of a lowest vertex under y = 0
  double largestEnergyRise = 0.0;   ///< J: the largest E_k − E_0 (mechanical energy)
  double rotationGain = 0.0;        ///< J: the summed bound on the orientation update's gain
};

/// Total mechanical energy, J: kinetic plus the potential −m g·x of World::potentialEnergy,
/// so the work gravity does is already in it and a free fall keeps it (semi-implicit Euler
/// even loses ½ m g² Δt² a step).
inline double mechanicalEnergy(const World& world) {
  return world.kineticEnergy() + world.potentialEnergy();
}

/// A bound on the kinetic energy the explicit orientation update adds to a body in a step, J,
/// with its angular momentum L held. The update (integrator.cpp, rotate) turns the box about ω by
/// the angle φ = 2 atan(|ω| Δt / 2); in body coordinates L turns by −φ about ω, becoming
/// L + Δ with |Δ| = 2 sin(φ/2) |L⊥| <= |ω| Δt / sqrt(1 + (|ω| Δt / 2)²) |L|. The rotational
/// energy ½ Lᵀ I⁻¹ L changes by ωᵀΔ + ½ Δᵀ I⁻¹ Δ, and ωᵀΔ = 0 because Δ is perpendicular to the
/// axis ω; so the update never removes energy and adds at most ½ |Δ|² / I_min. It vanishes
/// as Δt², but not for a fast spin at a large Δt: a 0.05 m needle spun at 30 rad/s for 1/10 s
/// gains a multiple of its energy in one step. `omega` is the angular velocity the update used.
inline double orientationGainBound(const RigidBody& body, const Vec3& omega, const Vec3& L,
                                   double dt) {
  if (body.immovable) return 0.0;
  const double theta = omega.norm() * dt;
  const double delta = theta / std::sqrt(1.0 + 0.25 * theta * theta) * L.norm();
  return 0.5 * delta * delta * body.IbodyInvDiag.maxCoeff();
}

/// The largest energy, J, one step of the impulse-based techniques can add to a body of mass m
/// (kg) through the gravity trick of \alg{COLLIDE L1-L6} (Guendelman et al. 2003, §7), whatever
/// its contacts: 3/2 m g² Δt². Contact passes act on u = v + g Δt, the velocity after the
/// step's gravity, with restitution in [−1, 0], so they never raise Σ ½ m |u|²; collisions act
/// on v with restitution <= 1 and never raise Σ ½ m |v|². Positions then advance by Δt u. For a
/// step from v to u the energy changes by ½ m |u|² − ½ m |v|² − m Δt g·u (the potential term),
/// which is at most m Δt g·(v − u) + ½ m g² Δt² per body; summed, by Cauchy-Schwarz,
/// Σ m Δt g·(−u) <= g Δt sqrt(M Σ m |u|²) <= g Δt sqrt(M · M g² Δt²) for a system at rest,
/// M g² Δt². The impulses may hand the whole step of free fall to upward motion: the pop of a
/// stack that \thesis{§5.2} damps away. The bound is summed over the movable bodies.
inline double gravityTrickGainBound(double mass, double g, double dt) {
  return 1.5 * mass * g * g * dt * dt;
}

/// The largest potential energy, J, FIXCONTACTCONSTRAINTS (\thesis{§4.4}, \alg{DAMPEDINTEGRATION L5}) can add
/// to a body in one step: it lifts the upper body of an interpenetrating pair, against gravity,
/// by at most fixLiftLimit (the larger of maxNudges nudges, 0.1 ℓ by default, and the distance
/// a vertex of the body can have travelled in the step), m g times that. A lift out of a
/// penetration the same step made gives back what the fall took; the bound covers a body lifted
/// out of one deeper than that (a box pressed into its support by a heavy load, or pushed
/// sideways into a taller one and nudged up its side). `body` holds the velocities the step
/// integrated its position with (those at the end of a damped step). One contact's worth per
/// body: bodies fixed against several supports in a step may exceed it.
inline double fixLiftGainBound(const RigidBody& body, const Vec3& gravity, double dt) {
  return body.mass * gravity.norm() * fixLiftLimit(body, FixContactParams{}, gravity, dt);
}

/// Runs `stepper` on a copy of the scene for its steps and checks, after every step k:
///  - every x, q, P and L of every body is finite;
///  - no body's lowest vertex lies under the ground (y = 0) by more than
///        S_k Δt + g Δt² + contactTolerance(ℓ),
///    while its centre is over the ground's 100 m square. In one step a vertex moves at most
///    Δt (|v| + g Δt) + Δt |ω| ρ (semi-implicit Euler moves the centre with the velocity after
///    gravity; the orientation update turns by at most |ω| Δt, moving a vertex at distance ρ by
///    at most ρ |ω| Δt). S_k is the largest |v| + |ω| ρ of any body at the start of the step:
///    a technique that resolves a contact only after a step has ended may find a vertex that
///    deep, but must push it back out, never let it go deeper (a box passing through the
///    ground falls on and fails within a step or two). The plain impulse step ("impulse") has
///    no position correction: what its contact passes leave of the step's fall, at most the
///    g Δt² gravity moves a resting body in a step, stays. Its tolerance grows by g Δt² a step
///    (k g Δt² after k steps): the sag chapters/impulse_damped/README.md measures;
///  - for damped integration ("damped"): the mechanical energy E_k never exceeds
///        E_{k−1} + Σ_i (G_rot,i + G_trick,i + G_fix,i) + 1e-9 |E|,
///    so neither does it exceed E_0 plus the sum of these over the steps. G_rot
///    (orientationGainBound, with the momenta at the end of the step and the larger of the
///    angular velocities they give at the start and end orientations) and G_trick
///    (gravityTrickGainBound) and G_fix (fixLiftGainBound, with the velocities at the end of
///    the step) are the energy sources the scheme
///    has; the last term is rounding. Everything else (collisions, contact passes, damping,
///    gravity) cannot add energy. The plain impulse step is not checked for energy: its shock
///    propagation (Guendelman et al. 2003, §8) stops a body against a lower one it treats as
///    immovable while that one is moving, which can add energy without a bound in the state.
inline StressOutcome runStressChecks(const RandomScene& scene, Stepper& stepper) {
  const bool damped = stepper.name() == "damped";
  const bool plainImpulse = stepper.name() == "impulse";
  const bool checkEnergy = damped;
  World world = scene.world;
  StressOutcome out;
  const double dt = scene.dt;
  const double g = world.gravity.norm();
  const double e0 = mechanicalEnergy(world);
  double before = e0;  // E_{k-1}
  double trick = 0.0;  // Σ G_trick, the same every step
  for (const RigidBody& b : world.bodies)
    if (!b.immovable) trick += gravityTrickGainBound(b.mass, g, dt);
  std::vector<Mat3> Rstart(world.bodies.size());
  for (int k = 1; k <= scene.steps; ++k) {
    double speed = 0.0;  // S_k, m/s
    for (std::size_t i = 0; i < world.bodies.size(); ++i) {
      const RigidBody& b = world.bodies[i];
      Rstart[i] = b.R;
      if (!b.immovable) speed = std::max(speed, b.v.norm() + b.omega.norm() * b.halfExtents.norm());
    }
    const StepStats stats = stepper.step(world, dt);
    out.steps = k;
    out.limitedSteps += stats.limitReached ? 1 : 0;
    for (std::size_t i = 0; i < world.bodies.size(); ++i) {
      const RigidBody& b = world.bodies[i];
      const BodyState& s = b.s;
      const std::string who = "step " + std::to_string(k) + ", body " + std::to_string(i) + ": ";
      if (!s.x.allFinite() || !s.q.coeffs().allFinite() || !s.P.allFinite() || !s.L.allFinite()) {
        out.failure = who + "state not finite";
        return out;
      }
      if (b.immovable || std::abs(s.x.x()) > 50.0 || std::abs(s.x.z()) > 50.0) continue;
      double lowest = s.x.y();
      for (int a = 0; a < 3; ++a) lowest -= b.halfExtents[a] * std::abs(b.R(1, a));
      out.deepestBelowGround = std::max(out.deepestBelowGround, -lowest);
      const double sag = plainImpulse ? static_cast<double>(k) * g * dt * dt : 0.0;
      const double tolerance =
          speed * dt + g * dt * dt + contactTolerance(b.halfExtents.minCoeff()) + sag;
      if (-lowest > tolerance) {
        std::ostringstream message;
        message << who << "lowest vertex " << -lowest << " m under the ground, more than "
                << tolerance << " m";
        out.failure = message.str();
        return out;
      }
    }
    double rotation = 0.0;
    double fix = 0.0;  // Σ G_fix, from the velocities the step ended with
    for (std::size_t i = 0; i < world.bodies.size(); ++i) {
      const RigidBody& b = world.bodies[i];
      if (b.immovable) continue;
      fix += fixLiftGainBound(b, world.gravity, dt);
      const Mat3 Iinv0 = Rstart[i] * b.IbodyInvDiag.asDiagonal() * Rstart[i].transpose();
      const Vec3 omega0 = Iinv0 * b.s.L;
      const Vec3 omega = omega0.norm() > b.omega.norm() ? omega0 : b.omega;
      rotation += orientationGainBound(b, omega, b.s.L, dt);
    }
    out.rotationGain += rotation;
    const double energy = mechanicalEnergy(world);
    out.largestEnergyRise = std::max(out.largestEnergyRise, energy - e0);
    const double allowed =
        rotation + trick + fix + 1e-9 * std::max(std::abs(energy), std::abs(before));
    if (checkEnergy && energy - before > allowed) {
      std::ostringstream message;
      message << "step " << k << ": mechanical energy rose by " << energy - before
              << " J, more than the " << allowed << " J the orientation update (" << rotation
              << " J), the gravity trick (" << trick << " J) and FIXCONTACTCONSTRAINTS (" << fix
              << " J) can add";
      out.failure = message.str();
      return out;
    }
    before = energy;
  }
  return out;
}

/// The scene ranges a technique can afford to run by the thousand: the chronological
/// techniques (basic colliding, analytic, the timewarps) bisect for every collision and, with
/// boxes resting on one another, meet the crowding collisions of \thesis{§4.3} up to their
/// event limits each step, so they get fewer boxes than the impulse-based ones.
inline RandomSceneSpec affordableSpec(const std::string& method) {
  RandomSceneSpec spec;
  const bool chronological = method != "impulse" && method != "damped";
  spec.maxBodies = chronological ? 3 : 10;
  if (chronological) spec.steps = 20;
  if (method == "impulse") spec.maxMassRatio = 10.0;
  return spec;
}

}  // namespace boxsim::testing
