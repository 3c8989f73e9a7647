/// \file
/// A world stepped in a frame where its gravity points down (gravity_frame.hpp).
#include "boxsim/core/gravity_frame.hpp"

#include <cmath>
#include <stdexcept>

namespace boxsim {

Quat turnGravityDown(const Vec3& gravity) {
  const double g = gravity.norm();
  if (!(g > 0.0) || !std::isfinite(g))
    throw std::invalid_argument("turnGravityDown: gravity must be finite and non-zero");
  const Vec3 down = -Vec3::UnitY();
  const Vec3 along = gravity / g;
  // Along +y the shortest rotation has no axis: a half turn about x (w = 0, x = 1) takes +y to
  // −y. Elsewhere the shortest rotation, about along × down.
  if (along.x() == 0.0 && along.z() == 0.0 && along.y() > 0.0) return Quat(0.0, 1.0, 0.0, 0.0);
  return Quat::FromTwoVectors(along, down).normalized();
}

namespace {
/// Whether the caller left body `now` as it was handed back (`then`): the same state and the
/// same mass, extents, mobility and friction, bit for bit.
bool unchanged(const RigidBody& now, const RigidBody& then) {
  return now.s.x == then.s.x && now.s.q.coeffs() == then.s.q.coeffs() && now.s.P == then.s.P &&
         now.s.L == then.s.L && now.immovable == then.immovable && now.mass == then.mass &&
         now.invMass == then.invMass && now.halfExtents == then.halfExtents &&
         now.IbodyInvDiag == then.IbodyInvDiag &&
         now.friction.muStatic == then.friction.muStatic &&
         now.friction.muDynamic == then.friction.muDynamic;
}
}  // namespace

void GravityFrame::turnIn(std::size_t i, const RigidBody& body) {
  RigidBody& turned = turned_.bodies[i];
  turned = body;
  turned.s.x = turn_ * body.s.x;
  turned.s.q = (turn_ * body.s.q).normalized();
  turned.s.P = turn_ * body.s.P;
  turned.s.L = turn_ * body.s.L;
  turned.updateDerived();
}

World& GravityFrame::enter(const World& world) {
  const std::size_t n = world.bodies.size();
  if (!built_ || world.gravity != gravity_ || turned_.bodies.size() != n) {
    turn_ = turnGravityDown(world.gravity);
    gravity_ = world.gravity;
    turned_ = world;
    turned_.gravity = Vec3(0.0, -world.gravity.norm(), 0.0);
    for (std::size_t i = 0; i < n; ++i) turnIn(i, world.bodies[i]);
    handedBack_ = world.bodies;
    built_ = true;
  } else {
    turned_.restitution = world.restitution;
    turned_.broadPhase = world.broadPhase;
    turned_.groundIndex = world.groundIndex;
    for (std::size_t i = 0; i < n; ++i)
      if (!unchanged(world.bodies[i], handedBack_[i])) {
        turnIn(i, world.bodies[i]);
        handedBack_[i] = world.bodies[i];
      }
  }
  entered_.resize(n);
  for (std::size_t i = 0; i < n; ++i) entered_[i] = turned_.bodies[i].s;
  return turned_;
}

void GravityFrame::leave(World& world) {
  const Quat back = turn_.conjugate();
  for (std::size_t i = 0; i < world.bodies.size(); ++i) {
    const BodyState& s = turned_.bodies[i].s;
    // A body the step left where it was keeps the caller's bits (an immovable one, a sleeper).
    if (s == entered_[i]) continue;
    RigidBody& body = world.bodies[i];
    body.s.x = back * s.x;
    body.s.q = (back * s.q).normalized();
    body.s.P = back * s.P;
    body.s.L = back * s.L;
    body.updateDerived();
    handedBack_[i] = body;
  }
}

}  // namespace boxsim
