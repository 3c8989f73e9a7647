#include "boxsim/exterior_rotation/sticking_integrators.hpp"

#include <Eigen/QR>
#include <cmath>
#include <stdexcept>

#include "boxsim/core/integrator.hpp"
#include "boxsim/exterior_rotation/constraint_jacobian.hpp"

namespace boxsim {

std::string stickingMethodName(StickingMethod method) {
  return enumName(kStickingMethodNames, method);
}

std::vector<StickingMethod> allStickingMethods() {
  std::vector<StickingMethod> methods;
  for (const EnumName<StickingMethod>& entry : kStickingMethodNames)
    methods.push_back(entry.value);
  return methods;
}

StickingMethod parseStickingMethod(const std::string& name) {
  return parseEnum(kStickingMethodNames, name, "sticking method");
}

namespace {

int contactCount(const StickingScene& scene) { return static_cast<int>(scene.contacts.size()); }

/// The time derivative of one body's Witkin–Baraff state under gravity and a wrench.
struct BodyRate {
  Vec3 x, P, L;
  Eigen::Vector4d q;
};

/// RK4 with the sticking forces solved again at every stage: the stage states are loaded into
/// a copy of the world (quaternions normalised there), solved, and their rates combined with
/// the classical weights 1, 2, 2, 1.
void rungeKutta4Resolved(StickingScene& scene, double dt) {
  World& world = scene.world;
  const std::size_t n = world.bodies.size();
  World stage = world;
  std::vector<BodyState> s0(n);
  for (std::size_t k = 0; k < n; ++k) s0[k] = world.bodies[k].s;
  const auto rates = [&](const std::vector<BodyState>& s) {
    for (std::size_t k = 0; k < n; ++k) {
      if (stage.bodies[k].immovable) continue;
      stage.bodies[k].s = s[k];
      stage.bodies[k].s.q.normalize();
      stage.bodies[k].updateDerived();
    }
    const StickingSolution f = solveStickingForces(stage, scene.points, contactCount(scene));
    std::vector<BodyRate> r(n);
    for (std::size_t k = 0; k < n; ++k) {
      const RigidBody& b = stage.bodies[k];
      const Quat w(0.0, b.omega.x(), b.omega.y(), b.omega.z());
      r[k] = BodyRate{b.v, b.mass * world.gravity + f.wrench[k].force, f.wrench[k].torque,
                      0.5 * (w * b.s.q).coeffs()};
    }
    return r;
  };
  const auto advanced = [&](const std::vector<BodyRate>& r, double h) {
    std::vector<BodyState> s = s0;
    for (std::size_t k = 0; k < n; ++k) {
      if (world.bodies[k].immovable) continue;
      s[k].x += h * r[k].x;
      s[k].P += h * r[k].P;
      s[k].L += h * r[k].L;
      s[k].q.coeffs() += h * r[k].q;
    }
    return s;
  };
  const std::vector<BodyRate> k1 = rates(s0);
  const std::vector<BodyRate> k2 = rates(advanced(k1, 0.5 * dt));
  const std::vector<BodyRate> k3 = rates(advanced(k2, 0.5 * dt));
  const std::vector<BodyRate> k4 = rates(advanced(k3, dt));
  const double sixth = dt / 6.0;
  for (std::size_t k = 0; k < n; ++k) {
    RigidBody& b = world.bodies[k];
    if (b.immovable) continue;
    b.s.x += sixth * (k1[k].x + 2.0 * k2[k].x + 2.0 * k3[k].x + k4[k].x);
    b.s.P += sixth * (k1[k].P + 2.0 * k2[k].P + 2.0 * k3[k].P + k4[k].P);
    b.s.L += sixth * (k1[k].L + 2.0 * k2[k].L + 2.0 * k3[k].L + k4[k].L);
    b.s.q.coeffs() += sixth * (k1[k].q + 2.0 * k2[k].q + 2.0 * k3[k].q + k4[k].q);
    b.s.q.normalize();
    b.updateDerived();
  }
}

/// One screw-motion step of one body (Murray, Li & Sastry, "A Mathematical Introduction to
/// Robotic Manipulation", 1994, §2.3, eq. 2.36; Featherstone, "Rigid Body Dynamics
/// Algorithms", 2008, §2.9 for the spatial velocity).
///
/// The spatial twist (ω, v_s), v_s = v − ω × x, changes at the rate (α, a − α × x − ω × v).
/// It is advanced with Euler, then the body is moved by exp(Δt [ω′, v_s′]): the rotation by
/// θ = |ω′| Δt about the axis ω′ together with the translation
/// V v_s′, V = Δt I + (1 − cos θ)/|ω′|² [ω′]× + (θ − sin θ)/|ω′|³ [ω′]×².
void screwStep(RigidBody& body, const Vec3& a, const Vec3& alpha, double dt) {
  const Vec3 x = body.s.x;
  const Vec3 omega1 = body.omega + dt * alpha;
  const Vec3 vs = body.v - body.omega.cross(x);
  const Vec3 vs1 = vs + dt * (a - alpha.cross(x) - body.omega.cross(body.v));
  const double w = omega1.norm();
  const double theta = w * dt;
  // Below θ = 1e-4 the closed forms lose digits to cancellation; their series to θ² are exact
  // to far below rounding there.
  const double c1 = theta < 1e-4 ? dt * dt * (0.5 - theta * theta / 24.0) : (1.0 - std::cos(theta)) / (w * w);
  const double c2 = theta < 1e-4 ? dt * dt * dt * (1.0 / 6.0 - theta * theta / 120.0)
                                 : (theta - std::sin(theta)) / (w * w * w);
  const Vec3 translation = dt * vs1 + c1 * omega1.cross(vs1) + c2 * omega1.cross(omega1.cross(vs1));
  const Quat turn = w > 0.0 ? Quat(Eigen::AngleAxisd(theta, omega1 / w)) : Quat::Identity();
  body.s.x = turn * x + translation;
  body.s.q = (turn * body.s.q).normalized();
  body.updateDerived();
  body.setVelocity(vs1 + omega1.cross(body.s.x));
  body.setAngularVelocity(omega1);
}

}  // namespace

ProjectionReport projectOntoConstraints(StickingScene& scene, const ProjectionParams& params) {
  if (!(params.positionTolerance > 0.0) || params.maxIterations < 1)
    throw std::invalid_argument("projection needs positionTolerance > 0 m and maxIterations >= 1");
  World& world = scene.world;
  const auto largest = [](const Eigen::VectorXd& C) {
    double e = 0.0;
    for (int i = 0; i < C.size() / 3; ++i) e = std::max(e, C.segment<3>(3 * i).norm());
    return e;
  };
  ProjectionReport report;
  for (;;) {
    const ConstraintJacobian jac(world, scene.points);
    const Eigen::VectorXd C = jac.positionError();
    const double error = largest(C);
    if (report.iterations == 0) report.errorBefore = error;
    report.errorAfter = error;
    if (error <= params.positionTolerance || report.iterations == params.maxIterations) break;
    const Eigen::MatrixXd WJt = jac.inverseMassTimesTransposed();
    const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(jac.J * WJt);
    const Eigen::VectorXd delta = -(WJt * cod.solve(C));
    for (std::size_t k = 0; k < world.bodies.size(); ++k) {
      const int c = jac.column(static_cast<int>(k));
      if (c < 0) continue;
      RigidBody& body = world.bodies[k];
      body.s.x += delta.segment<3>(c);
      const Vec3 turn = delta.segment<3>(c + 3);
      const double angle = turn.norm();
      if (angle > 0.0) body.s.q = (Quat(Eigen::AngleAxisd(angle, turn / angle)) * body.s.q).normalized();
      body.updateDerived();
    }
    ++report.iterations;
  }
  // The velocities onto the tangent space J w = 0, in the mass metric.
  const ConstraintJacobian jac(world, scene.points);
  const Eigen::MatrixXd WJt = jac.inverseMassTimesTransposed();
  const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(jac.J * WJt);
  const Eigen::VectorXd w = jac.velocities() - WJt * cod.solve(jac.J * jac.velocities());
  for (std::size_t k = 0; k < world.bodies.size(); ++k) {
    const int c = jac.column(static_cast<int>(k));
    if (c < 0) continue;
    world.bodies[k].setVelocity(w.segment<3>(c));
    world.bodies[k].setAngularVelocity(w.segment<3>(c + 3));
  }
  return report;
}

StickingSolution stepSticking(StickingScene& scene, StickingMethod method, double dt,
                              const ProjectionParams& projection) {
  if (!std::isfinite(dt) || dt <= 0.0)
    throw std::invalid_argument("a sticking step needs a finite dt > 0 s");
  World& world = scene.world;
  const StickingSolution f = solveStickingForces(world, scene.points, contactCount(scene));
  const auto constantForces = [&](Integrator integrator) {
    for (std::size_t k = 0; k < world.bodies.size(); ++k)
      integrateBody(world.bodies[k], dt, world.gravity, integrator, f.wrench[k]);
  };
  switch (method) {
    case StickingMethod::ForwardEuler: constantForces(Integrator::ForwardEuler); break;
    case StickingMethod::SemiImplicitEuler: constantForces(Integrator::SemiImplicitEuler); break;
    case StickingMethod::RungeKutta4ConstantForces: constantForces(Integrator::RungeKutta4); break;
    case StickingMethod::RungeKutta4ResolvedForces: rungeKutta4Resolved(scene, dt); break;
    case StickingMethod::ScrewEuler:
    case StickingMethod::ScrewEulerProjected:
      for (std::size_t k = 0; k < world.bodies.size(); ++k)
        if (!world.bodies[k].immovable) screwStep(world.bodies[k], f.a[k], f.alpha[k], dt);
      if (method == StickingMethod::ScrewEulerProjected) projectOntoConstraints(scene, projection);
      break;
  }
  return f;
}

}  // namespace boxsim
