/// \file
/// The first time of impact of a fast body within a step, by conservative advancement.
#include "boxsim/impulse_damped/continuous_collision.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/collision/separating_axis.hpp"
#include "boxsim/impulse_damped/predicted_positions.hpp"

namespace boxsim {

namespace {

/// Iterations of conservative advancement per pair. Each removes the whole gap at the closing
/// speed bound, so a pair coming straight at each other needs two or three; the cap only
/// stops a grazing pair, which is then taken to meet where the advancement stopped (early,
/// never late).
constexpr int kMaxAdvances = 64;

/// The body's pose at τ (s) into the step, as integrateObjectPositions would put it.
RigidBody poseAt(const RigidBody& body, double tau, const Vec3& gravityStep) {
  RigidBody moved = body;
  if (!moved.immovable && tau > 0.0) movePredicted(moved, tau, gravityStep);
  return moved;
}

/// m/s: the fastest a point of the body moves along the predicted motion.
double pointSpeedBound(const RigidBody& body, const Vec3& gravityStep) {
  if (body.immovable) return 0.0;
  return (body.v + gravityStep).norm() + body.omega.norm() * body.halfExtents.norm();
}

/// The first τ in [0, dt] at which bodies a and b come within `margin`, or dt. Within it
/// already: 0 when their centres approach along the separating axis (an impact under way),
/// else dt (a contact, the passes' business).
double pairTimeOfImpact(const World& world, int a, int b, double dt, double margin,
                        const Vec3& gravityStep) {
  const RigidBody& A = world.bodies[a];
  const RigidBody& B = world.bodies[b];
  const double speed = pointSpeedBound(A, gravityStep) + pointSpeedBound(B, gravityStep);
  if (!(speed > 0.0)) return dt;
  const auto velocity = [&](const RigidBody& body) {
    return body.immovable ? Vec3(Vec3::Zero()) : Vec3(body.v + gravityStep);
  };
  double tau = 0.0;
  for (int k = 0; k < kMaxAdvances; ++k) {
    const SeparatingAxisResult sat = separatingAxisTest(Obb::of(poseAt(A, tau, gravityStep)),
                                                        Obb::of(poseAt(B, tau, gravityStep)));
    const double gap = -sat.depth;
    if (gap < margin && k > 0) return tau;
    if (gap < margin) return sat.normal.dot(velocity(B) - velocity(A)) < 0.0 ? 0.0 : dt;
    tau += (gap - 0.5 * margin) / speed;
    if (tau >= dt) return dt;
  }
  return tau;
}

}  // namespace

double firstTimeOfImpact(const World& world, double dt, double margin,
                         const ContinuousCollisionParams& params) {
  if (!params.enabled) return dt;
  const Vec3 gravityStep = dt * world.gravity;
  const std::size_t n = world.bodies.size();
  // Each body's bounds over the step: its centre's path, widened by its half diagonal, which
  // holds every pose the predicted motion passes through.
  std::vector<Vec3> lo(n), hi(n);
  std::vector<char> fast(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const RigidBody& body = world.bodies[i];
    if (body.immovable) {
      obbBounds(Obb::of(body), 0.0, lo[i], hi[i]);
      continue;
    }
    const Vec3 end = body.s.x + dt * (body.v + gravityStep);
    const double rho = body.halfExtents.norm();
    lo[i] = body.s.x.cwiseMin(end).array() - rho;
    hi[i] = body.s.x.cwiseMax(end).array() + rho;
    fast[i] = dt * pointSpeedBound(body, gravityStep) > params.fastReach * body.halfExtents.minCoeff();
  }
  double first = dt;
  for (const auto& [a, b] : candidatePairs(world, lo, hi, margin))
    if (fast[a] || fast[b])
      first = std::min(first, pairTimeOfImpact(world, a, b, dt, margin, gravityStep));
  return first;
}

}  // namespace boxsim
