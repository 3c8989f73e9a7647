// Verification of the core: rigid body state, box inertia, integrators (closed-form answers and
// convergence order), the Newtonian impulse and roll-back.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "boxsim/core/gravity_frame.hpp"
#include "boxsim/core/integrator.hpp"
#include "boxsim/core/math.hpp"
#include "boxsim/core/newtonian_impulse.hpp"
#include "boxsim/core/pair_table.hpp"
#include "boxsim/core/world.hpp"

using namespace boxsim;

namespace {

// Position after n steps of size dt from x0, v0 under gravity g.
Vec3 freeFlight(Integrator integrator, double dt, int n, const Vec3& x0, const Vec3& v0) {
  World world;
  RigidBody b = RigidBody::box(Vec3(0.5, 0.5, 0.5), 2.0);
  b.s.x = x0;
  b.setVelocity(v0);
  world.add(b, "box");
  for (int k = 0; k < n; ++k) integrateWorld(world, dt, integrator);
  return world.bodies[0].s.x;
}

// A world without gravity holding one box of the given half extents (m) and mass (kg)
// spinning at omega (rad/s).
World spinnerWorld(const Vec3& halfExtents, double mass, const Vec3& omega) {
  World world;
  world.gravity = Vec3::Zero();
  RigidBody b = RigidBody::box(halfExtents, mass);
  b.setAngularVelocity(omega);
  world.add(b, "spinner");
  return world;
}

// Relative kinetic-energy error after time T of a torque-free box spinning about a tilted axis.
double spinEnergyError(double dt, double T, Vec3* Lend = nullptr, Vec3* L0out = nullptr,
                       Integrator integrator = Integrator::ForwardEuler) {
  World world = spinnerWorld(Vec3(0.5, 0.3, 0.1), 1.5, Vec3(0.3, 4.0, 0.8));
  const double e0 = world.kineticEnergy();
  const Vec3 L0 = world.bodies[0].s.L;
  const int n = static_cast<int>(std::lround(T / dt));
  for (int k = 0; k < n; ++k) integrateWorld(world, dt, integrator);
  if (Lend) *Lend = world.bodies[0].s.L;
  if (L0out) *L0out = L0;
  return std::abs(world.kineticEnergy() - e0) / e0;
}

}  // namespace

TEST_CASE("A unit cube of 1 kg has principal moments 1/6 kg m^2", "[core][closed_form]") {
  const Vec3 I = boxInertiaDiagonal(Vec3(0.5, 0.5, 0.5), 1.0);
  CHECK(I.x() == Approx(1.0 / 6.0).epsilon(1e-15));
  const Vec3 J = boxInertiaDiagonal(Vec3(1.0, 0.5, 0.25), 3.0);  // sides 2, 1, 0.5
  CHECK(J.x() == Approx(3.0 / 12.0 * (1.0 + 0.25)).epsilon(1e-15));
  CHECK(J.y() == Approx(3.0 / 12.0 * (4.0 + 0.25)).epsilon(1e-15));
  CHECK(J.z() == Approx(3.0 / 12.0 * (4.0 + 1.0)).epsilon(1e-15));
}

TEST_CASE("Bad box parameters are rejected", "[core][input]") {
  CHECK_THROWS_AS(RigidBody::box(Vec3(0.5, 0.0, 0.5), 1.0), std::invalid_argument);
  CHECK_THROWS_AS(RigidBody::box(Vec3(0.5, 0.5, 0.5), -1.0), std::invalid_argument);
  CHECK_THROWS_AS(RigidBody::box(Vec3(0.5, NAN, 0.5), 1.0), std::invalid_argument);
}

TEST_CASE("Free flight matches x0 + v0 t + g t^2 / 2 to first order in dt", "[core][closed_form]") {
  const Vec3 x0(0.0, 10.0, 0.0), v0(1.0, 3.0, -2.0), g = standardGravity();
  const double T = 1.0;
  for (Integrator integrator : {Integrator::ForwardEuler, Integrator::SemiImplicitEuler}) {
    double previous = 0.0;
    for (int n : {50, 100, 200, 400}) {
      const double dt = T / n;
      const Vec3 exact = x0 + v0 * T + 0.5 * g * T * T;
      const Vec3 x = freeFlight(integrator, dt, n, x0, v0);
      // Both Euler variants are exact for the linear part; their gravity error is exactly
      // ∓ g T dt / 2 (forward Euler lags by one step of velocity, semi-implicit leads by one).
      const double sign = integrator == Integrator::ForwardEuler ? -1.0 : 1.0;
      const Vec3 predictedError = sign * 0.5 * g * T * dt;
      CHECK((x - exact - predictedError).norm() < 1e-12);
      const double error = (x - exact).norm();
      if (previous > 0.0) CHECK(previous / error == Approx(2.0).epsilon(1e-9));
      previous = error;
    }
  }
}

TEST_CASE("A torque-free spinning box keeps L exactly and its energy to first order in dt",
          "[core][invariant]") {
  Vec3 L0, L1;
  const double T = 2.0;
  const double e1 = spinEnergyError(1e-3, T, &L1, &L0);
  // The Witkin-Baraff state stores L; with no torque nothing changes it.
  CHECK(L1 == L0);
  const double e2 = spinEnergyError(5e-4, T);
  const double e3 = spinEnergyError(2.5e-4, T);
  // Forward Euler is first order: halving dt halves the energy error (ratio 2, within 10%
  // for the higher-order terms at these step sizes).
  CHECK(e1 / e2 == Approx(2.0).epsilon(0.1));
  CHECK(e2 / e3 == Approx(2.0).epsilon(0.1));
  CHECK(e3 < 1e-2);
}

TEST_CASE("An immovable body ignores gravity and impulses", "[core][invariant]") {
  World world;
  const int ground = world.addGround(0.0);
  RigidBody box = RigidBody::box(Vec3(0.5, 0.5, 0.5), 1.0);
  box.s.x = Vec3(0.0, 0.5, 0.0);
  box.setVelocity(Vec3(0.0, -3.0, 0.0));
  const int b = world.add(box, "box");
  const BodyState before = world.bodies[ground].s;
  const double j = applyNewtonianImpulse(world.bodies[ground], world.bodies[b], Vec3(0, 0, 0),
                                         Vec3::UnitY(), 0.9);
  integrateWorld(world, 0.1, Integrator::ForwardEuler);
  CHECK(j > 0.0);
  CHECK(world.bodies[ground].s == before);
  CHECK(world.bodies[b].v.y() == Approx(0.9 * 3.0 - 0.981).epsilon(1e-12));
}

TEST_CASE("The Newtonian impulse conserves momentum and reverses the normal velocity times e",
          "[core][closed_form]") {
  World world;
  world.gravity = Vec3::Zero();
  RigidBody a = RigidBody::box(Vec3(0.5, 0.4, 0.3), 2.0);
  RigidBody b = RigidBody::box(Vec3(0.2, 0.6, 0.5), 0.7);
  a.s.q = Quat(Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()));
  a.updateDerived();
  b.s.x = Vec3(1.0, 0.1, -0.2);
  b.updateDerived();
  a.setVelocity(Vec3(1.0, 0.2, 0.0));
  a.setAngularVelocity(Vec3(0.5, -1.0, 2.0));
  b.setVelocity(Vec3(-2.0, 0.0, 0.5));
  const Vec3 p(0.5, 0.05, -0.1), n = Vec3(1.0, 0.2, -0.1).normalized();
  for (double e : {0.0, 0.5, 0.9, 1.0}) {
    RigidBody a1 = a, b1 = b;
    const double vBefore = relativeNormalVelocity(a1, b1, p, n);
    REQUIRE(vBefore < 0.0);
    const Vec3 momentum = a1.s.P + b1.s.P;
    // Angular momentum about the origin: L + x × P summed.
    const Vec3 angular = a1.s.L + a1.s.x.cross(a1.s.P) + b1.s.L + b1.s.x.cross(b1.s.P);
    applyNewtonianImpulse(a1, b1, p, n, e);
    CHECK((a1.s.P + b1.s.P - momentum).norm() < 1e-14);
    CHECK((a1.s.L + a1.s.x.cross(a1.s.P) + b1.s.L + b1.s.x.cross(b1.s.P) - angular).norm() < 1e-13);
    CHECK(relativeNormalVelocity(a1, b1, p, n) == Approx(-e * vBefore).margin(1e-13));
  }
}

TEST_CASE("Restoring a saved world state is a bit-exact roll-back", "[core][determinism]") {
  World world;
  world.addGround();
  RigidBody b = RigidBody::box(Vec3(0.5, 0.5, 0.5), 1.0);
  b.s.x = Vec3(0, 3, 0);
  b.setAngularVelocity(Vec3(1, 2, 3));
  world.add(b, "box");
  const WorldState saved = world.saveState();
  const RigidBody derivedBefore = world.bodies[1];
  integrateWorld(world, 0.37, Integrator::ForwardEuler);
  CHECK_FALSE(world.saveState() == saved);
  world.restoreState(saved);
  CHECK(world.saveState() == saved);
  CHECK(world.bodies[1].omega == derivedBefore.omega);
  CHECK(world.bodies[1].Iinv == derivedBefore.Iinv);
}

TEST_CASE("Runge-Kutta 4 is exact for free flight and fourth order for a torque-free spin",
          "[core][closed_form][rk4]") {
  // Constant acceleration: x(t) is a polynomial of degree 2, which RK4 integrates exactly.
  const Vec3 x0(1.0, 2.0, -0.5), v0(3.0, 4.0, 1.0), g(0.0, -9.81, 0.0);
  const double T = 1.0;
  const Vec3 exact = x0 + v0 * T + 0.5 * g * T * T;
  CHECK((freeFlight(Integrator::RungeKutta4, T, 1, x0, v0) - exact).norm() < 1e-12);
  // Torque-free spin of an asymmetric box about a tilted axis (the energy is conserved by the
  // exact motion): the error falls by about 2⁴ = 16 when the step halves, and L is kept exactly
  // (no torque acts on it).
  Vec3 L0, L1;
  const double coarse = spinEnergyError(1.0 / 60.0, 2.0, &L1, &L0, Integrator::RungeKutta4);
  const double fine = spinEnergyError(1.0 / 120.0, 2.0, nullptr, nullptr, Integrator::RungeKutta4);
  const double euler = spinEnergyError(1.0 / 60.0, 2.0);
  INFO("relative energy error over 2 s: RK4 " << coarse << " (dt 1/60), " << fine
                                             << " (dt 1/120); forward Euler " << euler);
  CHECK(coarse < 1e-3 * euler);
  CHECK(coarse / fine > 8.0);
  CHECK(L1 == L0);
}

namespace {

/// A free 0.5 x 0.2 x 0.1 m box of 1 kg spinning at ω = (1, 5, 0.1) rad/s, near its
/// intermediate axis (y), for 10 s at step dt with no gravity: the largest relative change of
/// its kinetic energy over the run, and whether L stayed bitwise the same.
double intermediateAxisEnergyChange(Integrator integrator, double dt, bool& sameL) {
  World world = spinnerWorld(Vec3(0.25, 0.1, 0.05), 1.0, Vec3(1.0, 5.0, 0.1));
  const double e0 = world.kineticEnergy();
  const Vec3 L0 = world.bodies[0].s.L;
  double worst = 0.0;
  for (long k = 0; k < std::lround(10.0 / dt); ++k) {
    integrateWorld(world, dt, integrator);
    worst = std::max(worst, std::abs(world.kineticEnergy() - e0) / e0);
  }
  sameL = world.bodies[0].s.L == L0;
  return worst;
}

}  // namespace

TEST_CASE("Split rotation keeps the energy of a box tumbling about its intermediate axis, Euler "
          "does not",
          "[core][invariant][split_rotation]") {
  bool sameL = false;
  const double forward = intermediateAxisEnergyChange(Integrator::ForwardEuler, 1.0 / 60, sameL);
  const double semi = intermediateAxisEnergyChange(Integrator::SemiImplicitEuler, 1.0 / 60, sameL);
  const double split60 = intermediateAxisEnergyChange(Integrator::SplitRotation, 1.0 / 60, sameL);
  CHECK(sameL);
  const double split120 = intermediateAxisEnergyChange(Integrator::SplitRotation, 1.0 / 120, sameL);
  INFO("largest relative energy change over 10 s: forward Euler " << forward
       << ", semi-implicit Euler " << semi << ", split rotation " << split60 << " (dt 1/60), "
       << split120 << " (dt 1/120)");
  // The explicit quaternion step gains energy without bound while the box tumbles (the
  // issue's probe: 417 %).
  CHECK(forward > 1.0);
  CHECK(semi > 1.0);
  // Each substep of the splitting is an exact rotation, so |L| in the body frame, and L in
  // the world, are kept; the energy error of a second-order symplectic splitting stays
  // bounded at O((|ω| Δt)²) of the energy: (5 rad/s / 60 Hz)² = 0.7 %, times the inertia
  // ratios of so flat a box (I_max / I_min = 5.2): under 5 %, and a quarter of it at half
  // the step (0.25 within 25 % for the higher-order terms).
  CHECK(split60 < 0.05);
  CHECK(split120 / split60 == Approx(0.25).epsilon(0.25));
}

TEST_CASE("A pair table holds what a map by ordered pair holds, through growth, swaps and clears",
          "[core][pair_table]") {
  // The same operations on a PairTable and on std::map: 3000 random pairs of 200 bodies, values
  // overwritten, (i, j) and (j, i) kept apart, then swapped with a second table and cleared.
  PairTable<int> table, other;
  std::map<std::pair<int, int>, int> reference;
  unsigned state = 12345u;
  const auto next = [&state] {
    state = state * 1664525u + 1013904223u;
    return static_cast<int>(state >> 8);
  };
  for (int k = 0; k < 3000; ++k) {
    const int i = next() % 200, j = next() % 200;
    table.at(i, j) = k;
    reference[{i, j}] = k;
  }
  REQUIRE(table.size() == reference.size());
  for (int i = 0; i < 200; ++i)
    for (int j = 0; j < 200; ++j) {
      const auto found = reference.find({i, j});
      const int* value = table.find(i, j);
      REQUIRE((value != nullptr) == (found != reference.end()));
      if (value) CHECK(*value == found->second);
    }
  CHECK(other.find(0, 0) == nullptr);  // an empty table answers without a slot
  other.at(7, 9) = 1;
  table.swap(other);
  CHECK(table.size() == 1);
  CHECK(*table.find(7, 9) == 1);
  CHECK(other.size() == reference.size());
  for (const auto& [pair, value] : reference) CHECK(*other.find(pair.first, pair.second) == value);
  other.clear();
  CHECK(other.size() == 0);
  for (const auto& [pair, value] : reference) CHECK(other.find(pair.first, pair.second) == nullptr);
}

TEST_CASE("Numbers are written as the shortest text that reads back to the same double, appended "
          "in place as on their own",
          "[core][format]") {
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<double> values = {0.0,        -0.0,      1e-5,       0.9,    1.0 / 60.0,
                                      -1.0 / 3.0, 1e300 / 7, 5e-324,     -2.5e-308,
                                      123456789012345678.0,  0.1 + 0.2,  inf,    -inf};
  std::string row = "x";
  std::string expected = "x";
  for (const double value : values) {
    const std::string text = shortestText(value);
    // Round trip: the text is the value, bit for bit (-0 keeps its sign).
    CHECK(sameBits(std::strtod(text.c_str(), nullptr), value));
    // No shorter text of %g digits reads back to it.
    if (std::isfinite(value) && value != 0.0) {
      char shorter[32];
      for (int digits = 1; digits < 17; ++digits) {
        std::snprintf(shorter, sizeof shorter, "%.*g", digits, value);
        if (std::strtod(shorter, nullptr) == value) {
          CHECK(text.size() <= std::string(shorter).size());
          break;
        }
      }
    }
    appendShortestText(row, value);
    row += ' ';
    expected += text + ' ';
  }
  CHECK(row == expected);
  CHECK(shortestText(std::numeric_limits<double>::quiet_NaN()).find("nan") != std::string::npos);
}

TEST_CASE("The turn of a gravity frame takes gravity to -y in any direction, and a frame hands back "
          "the bodies it did not move bit for bit",
          "[core][gravity_frame]") {
  // Directions: the z-up world, straight up (the half turn), a slant, and nearly down.
  const Vec3 gravities[] = {Vec3(0.0, 0.0, -9.81), Vec3(0.0, 9.81, 0.0), Vec3(3.0, -2.0, 5.0),
                            Vec3(1e-9, -9.81, 0.0)};
  for (const Vec3& g : gravities) {
    const Quat turn = turnGravityDown(g);
    INFO("gravity " << g.transpose());
    // A unit quaternion's rotation of a unit vector: a few ulp of 1.
    CHECK(std::abs(turn.norm() - 1.0) < 1e-15);
    CHECK((turn * g.normalized() - Vec3(0.0, -1.0, 0.0)).norm() < 1e-15);
  }
  CHECK(gravityPointsDown(Vec3(0.0, -9.81, 0.0)));
  CHECK(gravityPointsDown(Vec3::Zero()));
  CHECK_FALSE(gravityPointsDown(Vec3(0.0, 9.81, 0.0)));
  CHECK_FALSE(gravityPointsDown(Vec3(1e-300, -9.81, 0.0)));
  CHECK_THROWS_AS(turnGravityDown(Vec3::Zero()), std::invalid_argument);

  // A floor and a falling box under gravity along -z. The frame turns them so that gravity is
  // (0, -9.81, 0) and x, P and L turn with them; moving the box there and leaving writes the
  // box back turned back, and the floor, which did not move, keeps the caller's bits.
  World world;
  world.gravity = Vec3(0.0, 0.0, -9.81);
  world.add(RigidBody::immovableBox(Vec3(5.0, 5.0, 0.5)), "floor");
  RigidBody box = RigidBody::box(Vec3(0.5, 0.25, 0.5), 2.0);
  box.s.x = Vec3(0.3, -0.2, 2.0);
  box.s.q = axisAngleDegrees(Vec3(1.0, 2.0, 3.0), 30.0);
  box.s.P = Vec3(1.0, 0.0, -4.0);
  box.s.L = Vec3(0.0, 0.5, 0.0);
  box.updateDerived();
  world.add(box, "box");
  world.bodies[0].s.x = Vec3(0.1, 0.2, -0.5);
  world.bodies[0].updateDerived();
  const World before = world;
  GravityFrame frame;
  World& turned = frame.enter(world);
  CHECK(turned.gravity == Vec3(0.0, -9.81, 0.0));
  // Heights along gravity's opposite are the turned world's y.
  CHECK(turned.bodies[1].s.x.y() == Approx(2.0).margin(1e-15));
  CHECK(turned.bodies[1].s.P.y() == Approx(-4.0).margin(1e-15));
  // A step there: the box moves along +x of the turned world (the caller's +x too).
  turned.bodies[1].s.x += Vec3(0.5, 0.0, 0.0);
  frame.leave(world);
  CHECK((world.bodies[1].s.x - (before.bodies[1].s.x + Vec3(0.5, 0.0, 0.0))).norm() < 1e-15);
  CHECK(world.bodies[1].s.q.angularDistance(before.bodies[1].s.q) < 1e-15);
  CHECK((world.bodies[1].s.P - before.bodies[1].s.P).norm() < 1e-15);
  CHECK((world.bodies[1].s.L - before.bodies[1].s.L).norm() < 1e-15);
  CHECK(world.bodies[1].R.isApprox(world.bodies[1].s.q.toRotationMatrix(), 0.0));
  CHECK(world.bodies[0].s == before.bodies[0].s);
  // The next enter keeps the turned box as it was stepped (the caller did not change it), and
  // turns in a box the caller moved.
  const Vec3 kept = turned.bodies[1].s.x;
  CHECK(frame.enter(world).bodies[1].s.x == kept);
  world.bodies[1].s.x.z() += 1.0;
  CHECK(frame.enter(world).bodies[1].s.x.y() == Approx(kept.y() + 1.0).margin(1e-14));
}
