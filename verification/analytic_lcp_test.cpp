// The contact LCP of Baraff 1994 with the thesis' changes (§3.3.1): the pivoting solver against
// the LCP conditions and against enumeration of the clamped set.
#include <catch2/catch.hpp>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

#include "boxsim/analytic_lcp/analytic_stepper.hpp"
#include "boxsim/analytic_lcp/contact_matrix.hpp"
#include "boxsim/analytic_lcp/lcp_enumeration.hpp"
#include "boxsim/analytic_lcp/lcp_solver.hpp"
#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/io/scene_builders.hpp"
#include "seeded_random.hpp"
#include "test_worlds.hpp"
#include "workload.hpp"

using namespace boxsim;
using boxsim::testing::groundWorld;
using boxsim::testing::SeededRandom;

namespace {

/// A random feasible LCP with a symmetric positive semidefinite A = B Bᵀ (B n × k, singular
/// when k < n) and b = −A z0 + w0 with z0, w0 >= 0, so z0 is feasible and a solution exists
/// (a feasible monotone LCP is solvable).
std::pair<MatX, VecX> randomLcp(SeededRandom& random, int n, int k) {
  MatX B(n, k);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < k; ++j) B(i, j) = random.uniform(-1.0, 1.0);
  const MatX A = B * B.transpose();
  VecX z0(n), w0(n);
  for (int i = 0; i < n; ++i) {
    z0[i] = random.uniform(0.0, 1.0) < 0.5 ? 0.0 : random.uniform(0.0, 2.0);
    w0[i] = random.uniform(0.0, 1.0) < 0.5 ? 0.0 : random.uniform(0.0, 2.0);
  }
  return {A, VecX(-A * z0 + w0)};
}

LcpParams exact() {
  LcpParams p;
  p.epsilon = 1e-10;  // in units of |b| ~ 1: the LCP itself, not the thesis' physical tolerance
  return p;
}

}  // namespace

TEST_CASE("Baraff's pivoting solves random positive semidefinite LCPs, singular ones included",
          "[analytic_lcp][lcp][reference]") {
  SeededRandom random(1994);
  int singular = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const int n = random.integer(1, 12);
    const int k = random.integer(1, n + 2);
    singular += k < n;
    const auto [A, b] = randomLcp(random, n, k);
    LcpParams params = exact();
    params.linearSolver = static_cast<LcpLinearSolver>(trial % 3);
    const LcpResult r = solveContactLcp(A, b, params);
    INFO("trial " << trial << ", n " << n << ", rank <= " << k << ", solver "
                  << static_cast<int>(params.linearSolver) << ": " << r.failure);
    REQUIRE(r.converged);
    // The conditions, scaled by the problem (lcpViolation); ε and rounding through at most
    // n pivots of a well-scaled problem stay far below 1e-7.
    CHECK(lcpViolation(A, b, r.f) < 1e-7);
    // a is unique for symmetric positive semidefinite A: the reference must give the same.
    const std::optional<VecX> reference = enumerateContactLcp(A, b, 1e-9);
    REQUIRE(reference.has_value());
    const VecX aReference = A * *reference + b;
    CHECK((r.a - aReference).cwiseAbs().maxCoeff() < 1e-6 * std::max(1.0, b.cwiseAbs().maxCoeff()));
  }
  CHECK(singular > 100);
}

TEST_CASE("Baraff's drive_to_zero as printed, with Gaussian elimination: the thesis' settings",
          "[analytic_lcp][lcp][thesis]") {
  // snapToBounds off and Gaussian elimination (thesis §3.3.1) on nonsingular random LCPs: the
  // conditions still hold, and maxstep keeps every force >= 0 up to the rounding of the
  // pivots, so the clamp of §3.3.1 has nothing of physical size to remove.
  SeededRandom random(2003);
  double mostNegative = 0.0;
  for (int trial = 0; trial < 200; ++trial) {
    const int n = random.integer(1, 12);
    const auto [A, b] = randomLcp(random, n, n + 2);
    LcpParams params = exact();
    params.linearSolver = LcpLinearSolver::GaussianElimination;
    params.snapToBounds = false;
    params.clampNegativeForces = false;
    const LcpResult r = solveContactLcp(A, b, params);
    INFO("trial " << trial << ", n " << n << ": " << r.failure);
    REQUIRE(r.converged);
    CHECK(lcpViolation(A, b, r.f) < 1e-7);
    const double fScale = std::max(1.0, b.cwiseAbs().maxCoeff()) / A.diagonal().maxCoeff();
    mostNegative = std::min(mostNegative, r.mostNegativeForce / fScale);
    const std::optional<VecX> reference = enumerateContactLcp(A, b, 1e-9);
    REQUIRE(reference.has_value());
    CHECK((r.a - (A * *reference + b)).cwiseAbs().maxCoeff() <
          1e-6 * std::max(1.0, b.cwiseAbs().maxCoeff()));
  }
  // Rounding through at most a few dozen pivots of a well-scaled problem: far below 1e-10.
  CHECK(mostNegative > -1e-10);
}

TEST_CASE("Redundant contacts: four coplanar corners give a singular A and still a solution",
          "[analytic_lcp][lcp][singular]") {
  // A unit cube of 1 kg on a plane, four corner contacts: a_i = n · (acceleration of corner i)
  // = J_i M⁻¹ J_jᵀ f_j + b_i, J_i = (n, r_i × n). Three of the four rows are independent.
  const double m = 1.0, I = m / 6.0;  // unit cube: I = m (1² + 1²) / 12
  const Vec3 n = Vec3::UnitY();
  MatX J(4, 6);
  int row = 0;
  for (double x : {-0.5, 0.5})
    for (double z : {-0.5, 0.5}) {
      const Vec3 r(x, -0.5, z);
      J.row(row).head<3>() = n.transpose();
      J.row(row).tail<3>() = r.cross(n).transpose();
      ++row;
    }
  Eigen::Matrix<double, 6, 6> Minv = Eigen::Matrix<double, 6, 6>::Zero();
  Minv.diagonal() << 1 / m, 1 / m, 1 / m, 1 / I, 1 / I, 1 / I;
  const MatX A = J * Minv * J.transpose();
  const VecX b = VecX::Constant(4, -9.81);  // gravity, at rest
  REQUIRE(A.fullPivLu().rank() == 3);
  for (const LcpLinearSolver solver : {LcpLinearSolver::CompleteOrthogonal, LcpLinearSolver::Ldlt,
                                       LcpLinearSolver::IncrementalCholesky,
                                       LcpLinearSolver::GaussianElimination}) {
    LcpParams params;
    params.linearSolver = solver;
    const LcpResult r = solveContactLcp(A, b, params);
    INFO("solver " << static_cast<int>(solver) << ": " << r.failure);
    CHECK(r.converged);
    // The net force holds the weight and the net torque is zero: the box does not accelerate.
    const VecX wrench = J.transpose() * r.f;
    CHECK(wrench[1] == Approx(m * 9.81).epsilon(1e-9));
    CHECK(wrench.tail<3>().norm() < 1e-9);
    CHECK(r.a.cwiseAbs().maxCoeff() < 1e-9);
    CHECK(r.f.minCoeff() >= 0.0);
  }
}

TEST_CASE("The thesis' tolerance: a contact approaching slower than eps gets no force",
          "[analytic_lcp][lcp]") {
  // One contact whose points accelerate into each other at 5e-6 m/s², below ε = 1e-5
  // (\thesis{§3.3.1}): left alone. With ε = 0 (Baraff's a_d < 0) it is driven to exactly zero.
  MatX A(1, 1);
  A << 2.0;
  VecX b(1);
  b << -5e-6;
  const LcpResult tolerant = solveContactLcp(A, b, LcpParams{});
  CHECK(tolerant.f[0] == 0.0);
  CHECK(tolerant.a[0] == -5e-6);
  LcpParams strict;
  strict.epsilon = 0.0;
  const LcpResult exactResult = solveContactLcp(A, b, strict);
  CHECK(exactResult.f[0] == Approx(2.5e-6));
  CHECK(std::abs(exactResult.a[0]) < 1e-18);
  // A positive coupling: driving the first contact pushes the second apart, which then needs
  // no force; the order (most negative first) is Baraff's free choice made deterministic.
  MatX A2(2, 2);
  A2 << 2.0, 1.0, 1.0, 2.0;
  VecX b2(2);
  b2 << -1.0, -0.2;
  const LcpResult r = solveContactLcp(A2, b2, LcpParams{});
  CHECK(r.f[0] == Approx(0.5));
  CHECK(r.f[1] == 0.0);
  CHECK(r.a[1] == Approx(0.3));
}

TEST_CASE("Bad LCP input is refused with the shapes named", "[analytic_lcp][lcp][errors]") {
  MatX A = MatX::Identity(2, 2);
  VecX b = VecX::Zero(3);
  CHECK_THROWS_WITH(solveContactLcp(A, b), Catch::Contains("2 x 2") && Catch::Contains("3"));
  VecX nan(2);
  nan << 0.0, std::nan("");
  CHECK_THROWS_WITH(solveContactLcp(A, nan), Catch::Contains("finite"));
}

// ---------------------------------------------------------------------------------------------
// The contact matrix of a world (contact_matrix.hpp).


namespace {

constexpr double kG = 9.81;

/// Solves the world's contact LCP as it stands and returns the forces with the contacts.
std::pair<std::vector<PointContact>, LcpResult> solveWorld(const World& world) {
  const std::vector<PointContact> contacts = pointContacts(world, findContacts(world, 1e-6));
  MatX A;
  VecX b;
  contactMatrix(world, contacts, A, b);
  return {contacts, solveContactLcp(A, b)};
}

/// The largest linear and angular acceleration of any movable body under f.
double largestAcceleration(const World& world, const std::vector<PointContact>& contacts,
                           const VecX& f) {
  std::vector<Vec3> linear, angular;
  bodyAccelerations(world, contacts, f, linear, angular);
  double worst = 0.0;
  for (std::size_t k = 0; k < linear.size(); ++k)
    worst = std::max({worst, linear[k].norm(), angular[k].norm()});
  return worst;
}

}  // namespace

TEST_CASE("A cube resting on the ground: the contact forces carry its weight and it does not accelerate",
          "[analytic_lcp][contact_matrix]") {
  World world = groundWorld();
  addTower(world, TowerSpec{1});
  const auto [contacts, r] = solveWorld(world);
  REQUIRE(contacts.size() == 4);
  REQUIRE(r.converged);
  double up = 0.0;
  for (std::size_t i = 0; i < contacts.size(); ++i) up += r.f[static_cast<int>(i)] * std::abs(contacts[i].normal.y());
  CHECK(up == Approx(kG).epsilon(1e-9));
  // ε = 1e-5 m/s² may leave that much acceleration; rounding is far below.
  CHECK(largestAcceleration(world, contacts, r.f) < 1e-5);
}

TEST_CASE("A tower of 6: each level's contacts carry the weight above them",
          "[analytic_lcp][contact_matrix]") {
  World world = groundWorld();
  const int count = 6;
  addTower(world, TowerSpec{count});
  const auto [contacts, r] = solveWorld(world);
  REQUIRE(r.converged);
  // Load through the contacts under box k (bodies 1..count from the bottom): (count - k + 1) m g.
  std::vector<double> load(world.bodies.size(), 0.0);
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const PointContact& c = contacts[i];
    const int upper = world.bodies[c.a].s.x.y() > world.bodies[c.b].s.x.y() ? c.a : c.b;
    load[upper] += r.f[static_cast<int>(i)] * std::abs(c.normal.y());
  }
  for (int k = 1; k <= count; ++k) {
    INFO("box " << k);
    CHECK(load[k] == Approx((count - k + 1) * kG).epsilon(1e-8));
  }
  CHECK(largestAcceleration(world, contacts, r.f) < 1e-5);
  // The reference agrees on the accelerations (forces are not unique: 4 corners per level).
  MatX A;
  VecX b;
  contactMatrix(world, contacts, A, b);
  if (contacts.size() <= 16) {
    const std::optional<VecX> reference = enumerateContactLcp(A, b, 1e-9);
    REQUIRE(reference);
    CHECK((A * *reference + b - r.a).cwiseAbs().maxCoeff() < 1e-5);
  }
}

TEST_CASE("A pyramid of base 4 stands under its LCP forces", "[analytic_lcp][contact_matrix]") {
  World world = groundWorld();
  addPyramid(world, PyramidSpec{4});
  const auto [contacts, r] = solveWorld(world);
  REQUIRE(r.converged);
  MatX A;
  VecX b;
  contactMatrix(world, contacts, A, b);
  CHECK(lcpViolation(A, b, r.f) < 1e-7);
  CHECK(r.f.minCoeff() >= 0.0);
  CHECK(largestAcceleration(world, contacts, r.f) < 1e-5);
}

TEST_CASE("The contact matrix matches accelerations computed body by body", "[analytic_lcp][contact_matrix]") {
  // Random bodies with random velocities and random synthetic contacts between them. Column j
  // of A is the change of every a_i when contact j pushes with 1 N, and b is a with no force;
  // both are recomputed here from bodyAccelerations (Newton-Euler per body) and the point
  // kinematics p̈ = v̇ + ω̇ × r + ω × (ω × r), a second path to the same quantities.
  SeededRandom random(31);
  for (int trial = 0; trial < 50; ++trial) {
    World world = groundWorld();
    for (int k = 0; k < 4; ++k) {
      RigidBody box = RigidBody::box(random.vector(0.2, 1.0), random.uniform(0.5, 3.0));
      box.s.x = random.vector(-2.0, 2.0);
      box.s.q = random.rotation();
      box.updateDerived();
      box.setVelocity(random.vector(-1.0, 1.0));
      box.setAngularVelocity(random.vector(-2.0, 2.0));
      world.bodies.push_back(box);
      world.names.push_back("box");
    }
    std::vector<PointContact> contacts;
    for (int i = 0; i < 6; ++i) {
      PointContact c;
      c.a = random.integer(0, 4);
      do c.b = random.integer(0, 4); while (c.b == c.a);
      c.point = random.vector(-2.0, 2.0);
      c.normal = random.vector(-1.0, 1.0).normalized();
      c.normalRate = random.vector(-1.0, 1.0);
      contacts.push_back(c);
    }
    MatX A;
    VecX b;
    contactMatrix(world, contacts, A, b);
    const auto relativeAcceleration = [&](const VecX& f, bool withFreeTerms) {
      std::vector<Vec3> linear, angular;
      bodyAccelerations(world, contacts, f, linear, angular);
      VecX a(contacts.size());
      for (std::size_t i = 0; i < contacts.size(); ++i) {
        const PointContact& c = contacts[i];
        Vec3 p[2];
        for (int s = 0; s < 2; ++s) {
          const int k = s ? c.b : c.a;
          const RigidBody& body = world.bodies[k];
          const Vec3 r = c.point - body.s.x;
          p[s] = body.immovable ? Vec3(Vec3::Zero())
                                : Vec3(linear[k] + angular[k].cross(r) +
                                       body.omega.cross(body.omega.cross(r)));
        }
        const Vec3 dv = world.bodies[c.b].pointVelocity(c.point) - world.bodies[c.a].pointVelocity(c.point);
        a[static_cast<int>(i)] = c.normal.dot(p[1] - p[0]) + (withFreeTerms ? 2.0 * c.normalRate.dot(dv) : 0.0);
      }
      return a;
    };
    const VecX free = relativeAcceleration(VecX::Zero(contacts.size()), true);
    CHECK((free - b).cwiseAbs().maxCoeff() < 1e-9);
    for (int j = 0; j < static_cast<int>(contacts.size()); ++j) {
      VecX unit = VecX::Zero(contacts.size());
      unit[j] = 1.0;
      const VecX column = relativeAcceleration(unit, true) - free;
      CHECK((column - A.col(j)).cwiseAbs().maxCoeff() < 1e-9);
    }
    CHECK((A - A.transpose()).cwiseAbs().maxCoeff() == 0.0);
    CHECK(Eigen::SelfAdjointEigenSolver<MatX>(A).eigenvalues().minCoeff() > -1e-9);
  }
}

TEST_CASE("The thesis' epsilon ends Baraff's loop: at 0 the solvers that refactor per pivot cycle on "
          "a resting pyramid's LCPs, at 1e-8 and 1e-5 they stop, and every returned force is a "
          "solution to rounding",
          "[analytic_lcp][lcp][epsilon]") {
  // The contact LCPs of a touching pyramid of base 5 (140 contacts) at every fifth step of 1 s
  // under the analytic method, fewer under a reduced workload (the s3_3_epsilon_sweep figure
  // runs more scenes and every solver).
  World world = groundWorld();
  PyramidSpec spec;
  spec.base = 5;
  addPyramid(world, spec);
  std::vector<std::pair<MatX, VecX>> problems;
  AnalyticStepper stepper;
  const long samples = std::max(3L, testing::scaledCount(12));
  for (int k = 0; k < 5 * samples; ++k) {
    if (k % 5 == 0) {
      MatX A;
      VecX b;
      contactMatrix(world, pointContacts(world, findContacts(world, 1e-3)), A, b);
      problems.emplace_back(A, b);
    }
    stepper.step(world, 1.0 / 60.0);
  }
  const auto run = [&problems](double epsilon, LcpLinearSolver solver, bool snap) {
    LcpParams params;
    params.epsilon = epsilon;
    params.linearSolver = solver;
    params.snapToBounds = snap;
    int cycled = 0;
    long pivots = 0;
    double worst = 0.0;
    for (const auto& [A, b] : problems) {
      const LcpResult r = solveContactLcp(A, b, params);
      cycled += r.converged ? 0 : 1;
      pivots += r.pivots;
      worst = std::max(worst, lcpViolation(A, b, r.f));
    }
    INFO("epsilon " << epsilon << ", solver " << lcpLinearSolverName(solver) << ", snap " << snap
                    << ": " << cycled << " of " << problems.size() << " cycled, " << pivots
                    << " pivots, worst violation " << worst);
    // Cycling or not, what is returned solves the LCP to rounding: the loop at epsilon 0 chases
    // accelerations of rounding size.
    CHECK(worst < 1e-10);
    return std::pair<int, long>(cycled, pivots);
  };
  const int n = static_cast<int>(problems.size());
  for (const double epsilon : {1e-8, 1e-5}) {
    for (const bool snap : {false, true}) {
      CHECK(run(epsilon, LcpLinearSolver::IncrementalCholesky, snap).first == 0);
      CHECK(run(epsilon, LcpLinearSolver::GaussianElimination, snap).first == 0);
    }
  }
  // At epsilon 0, LDLT and Gaussian elimination (the thesis' solver) cycle on most of the
  // pyramid's problems, and take several times the pivots; the grown Cholesky factor with the
  // bounds snapped converges on every one.
  const auto ldlt0 = run(0.0, LcpLinearSolver::Ldlt, true);
  const auto gauss0 = run(0.0, LcpLinearSolver::GaussianElimination, true);
  CHECK(2 * ldlt0.first > n);
  CHECK(2 * gauss0.first > n);
  CHECK(ldlt0.second > 5 * run(1e-5, LcpLinearSolver::Ldlt, true).second);
  CHECK(run(0.0, LcpLinearSolver::IncrementalCholesky, true).first == 0);
}
