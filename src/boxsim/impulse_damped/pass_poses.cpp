/// \file
/// Where each body stands in a pass of the once-per-step gathering.
#include "boxsim/impulse_damped/pass_poses.hpp"

#include "boxsim/collision/broad_phase.hpp"

namespace boxsim {

void PassPoses::startPass(std::size_t n) {
  fastAtPredicted_.assign(n, 0);
  displaced_.assign(n, 0);
  partnerAtPredicted_.assign(n, 0);
  saved_.resize(n);
  partners_.clear();
}

void PassPoses::prepare(const RigidBody& body, int i, double dt, const Vec3& gravityStep,
                        std::uint64_t buildStamp, StampCounter& stamps) {
  PredictedPose& p = predicted_[i];
  // movePredicted reads x, q (unchanged since the build), v and ω; the velocities it leaves
  // come from P and L: with all of them as before, it would compute the same pose, bit for bit.
  if (p.stamp > buildStamp && sameBits(p.v, body.v) && sameBits(p.omega, body.omega) &&
      sameBits(p.P, body.s.P) && sameBits(p.L, body.s.L))
    return;
  RigidBody moved = body;
  movePredicted(moved, dt, gravityStep);
  p.P = body.s.P;
  p.L = body.s.L;
  p.v = body.v;
  p.omega = body.omega;
  p.x = moved.s.x;
  p.q = moved.s.q;
  p.R = moved.R;
  p.Iinv = moved.Iinv;
  p.vPredicted = moved.v;
  p.omegaPredicted = moved.omega;
  obbBounds(Obb::of(moved), 0.0, p.lo, p.hi);
  p.stamp = stamps.next();
}

void PassPoses::standPartner(int i) {
  partnerAtPredicted_[i] = 1;
  partners_.push_back(i);
}

void PassPoses::moveToPredicted(World& world, int i) {
  if (displaced_[i] || !atPredicted(i)) return;
  RigidBody& body = world.bodies[i];
  const PredictedPose& p = predicted_[i];
  saved_[i] = SavedPose{body.s.x, body.s.q, body.R, body.Iinv, false};
  body.s.x = p.x;
  body.s.q = p.q;
  body.R = p.R;
  body.Iinv = p.Iinv;
  body.v = p.vPredicted;
  body.omega = p.omegaPredicted;
  displaced_[i] = 1;
}

void PassPoses::putBack(World& world, int i) {
  if (displaced_[i]) {
    restorePose(world.bodies[i], saved_[i]);
    displaced_[i] = 0;
  } else {
    world.bodies[i].updateVelocities();
  }
}

}  // namespace boxsim
