/// \file
/// The interactive demo's scene, stepping, shots and display (demo.hpp).
#include "demo.hpp"

#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "boxsim/impulse_damped/damped_integration.hpp"
#include "boxsim/io/scene_builders.hpp"
#include "boxsim/techniques.hpp"

namespace boxsim::web {

namespace {

constexpr double kDt = 1.0 / 60.0;  // s

/// The scene of `name`, as the shipped scene files of chapters/impulse_damped/scenes build it
/// (pyramid10_shot.json without its timed shot: here the page shoots).
World buildScene(const std::string& name) {
  World world;
  if (name == "pyramid") {
    world.addGround(0.0, 30.0);
    addPyramid(world, PyramidSpec{});
  } else if (name == "clump") {
    world.addGround(0.0, 150.0);
    addClump(world, ClumpSpec{});
  } else if (name == "die") {
    world.addGround(0.0, 10.0);
    addDie(world, DieSpec{});
  } else if (name == "tower") {
    world.addGround(0.0, 20.0);
    addTower(world, TowerSpec{});
  } else if (name == "clump_ground") {
    world.restitution = 0.5;
    world.addGround(0.0, 50.0);
    ClumpSpec spec;
    spec.center = Vec3(0.0, 5.0, 0.0);
    spec.target = Vec3::Zero();
    addClump(world, spec);
  } else if (name == "pile") {
    world.restitution = 0.0;
    world.addGround(0.0, 20.0);
    ClumpSpec spec;
    spec.count = 343;
    spec.spacing = 1.5;
    spec.center = Vec3(0.0, 5.5, 0.0);
    spec.speed = 3.0;
    spec.spin = 6.0;
    addClump(world, spec);
  } else if (name == "clump1000") {
    world.addGround(0.0, 150.0);
    ClumpSpec spec;
    spec.count = 1000;
    addClump(world, spec);
  } else {
    throw std::invalid_argument("unknown scene '" + name +
                                "'; known: pyramid, clump, die, tower, clump_ground, pile, clump1000");
  }
  return world;
}

std::unique_ptr<Stepper> buildStepper(const DemoSettings& s) {
  if (s.method == "damped") {
    DampedIntegrationParams params;
    params.sleep.enabled = s.sleep;
    params.useGeometricStability = s.geometricStability;
    return std::make_unique<DampedIntegrationStepper>(params);
  }
  if (s.method != "impulse" && s.method != "analytic" && s.method != "basic_colliding")
    throw std::invalid_argument("unknown method '" + s.method +
                                "'; the demo has damped, impulse, analytic, basic_colliding");
  if (!s.sleep || !s.geometricStability)
    throw std::invalid_argument("sleeping and geometric stability are switches of damped "
                                "integration; method '" + s.method + "' has neither");
  return makeStepper(s.method);
}

}  // namespace

Demo::Demo(const DemoSettings& settings)
    : settings_(settings), world_(buildScene(settings.scene)), stepper_(buildStepper(settings)) {
  // The shots wait, immovable, far from the scene until fired (World::addLaunched).
  firstShot_ = static_cast<int>(world_.bodies.size());
  for (int k = 0; k < kShots; ++k) {
    RigidBody shot = RigidBody::box(Vec3::Constant(0.5), 1.0);
    shot.s.x = Vec3(1000.0 + 4.0 * k, 0.5, 1000.0);
    shot.updateDerived();
    world_.addLaunched(shot, "shot" + std::to_string(k), std::numeric_limits<double>::infinity());
  }
  if (!(settings.friction >= 0.0) || !std::isfinite(settings.friction))
    throw std::invalid_argument("friction must be a finite μ >= 0 (0: the thesis' frictionless "
                                "contact), not " + std::to_string(settings.friction));
  for (RigidBody& body : world_.bodies) body.friction = Friction{settings.friction, settings.friction};
  for (const RigidBody& body : world_.bodies) start_.push_back(body.s.x);
  if (settings.filter != "none" && settings.filter != "box" && settings.filter != "envelope")
    throw std::invalid_argument("unknown filter '" + settings.filter + "'; known: none, box, envelope");
  recorder_ = std::make_unique<Recorder>(world_, std::map<std::string, std::string>{}, *this);
  recorder_->capture(world_, time_);
}

void Demo::begin(const std::map<std::string, std::string>&,
                 const std::vector<TrajectoryBody>& bodies) {
  if (settings_.filter == "box") boxFilter_ = std::make_unique<CausalBoxFilter>(bodies);
  if (settings_.filter == "envelope") envelopeFilter_ = std::make_unique<CausalEnvelopeFilter>(bodies);
}

void Demo::push(const TrajectoryFrame& recorded) {
  TrajectoryFrame frame = recorded;
  if (boxFilter_) frame = boxFilter_->push(frame);
  if (envelopeFilter_) frame = envelopeFilter_->push(frame);
  poses_.clear();
  for (std::size_t i = 0; i < frame.x.size(); ++i) {
    poses_.insert(poses_.end(), frame.x[i].data(), frame.x[i].data() + 3);
    poses_.insert(poses_.end(), frame.q[i].coeffs().data(), frame.q[i].coeffs().data() + 4);
  }
}

int Demo::step() {
  world_.applyLaunches(time_);
  const StepStats stats = stepper_->step(world_, kDt);
  ++steps_;
  time_ = static_cast<double>(steps_) * kDt;
  recorder_->capture(world_, time_, stats);
  return stats.events;
}

bool Demo::shoot(const Vec3& from, const Vec3& direction) {
  if (shotsFired_ == kShots || !(direction.norm() > 0.0)) return false;
  const int body = firstShot_ + shotsFired_;
  RigidBody& shot = world_.bodies[static_cast<std::size_t>(body)];
  shot.s.x = from;
  shot.s.q = Quat::Identity();
  shot.updateDerived();
  Launch& launch = world_.launches[static_cast<std::size_t>(shotsFired_)];
  launch.velocity = kShotSpeed * direction.normalized();
  launch.time = time_;  // launched at the start of the next step
  start_[static_cast<std::size_t>(body)] = from;
  ++shotsFired_;
  return true;
}

std::vector<double> Demo::halfExtents() const {
  std::vector<double> out;
  for (const RigidBody& b : world_.bodies) out.insert(out.end(), b.halfExtents.data(), b.halfExtents.data() + 3);
  return out;
}

std::vector<double> Demo::sceneBodies() const {
  std::vector<double> out;
  for (const RigidBody& b : world_.bodies) {
    // 0 marks an immovable body: the ground, and a shot waiting for its launch (the engines
    // give it the 1 kg of boxsim's shots when it is fired).
    const double mass = b.immovable ? 0.0 : b.mass;
    out.insert(out.end(), b.halfExtents.data(), b.halfExtents.data() + 3);
    out.insert(out.end(), b.s.x.data(), b.s.x.data() + 3);
    out.insert(out.end(), b.s.q.coeffs().data(), b.s.q.coeffs().data() + 4);
    out.insert(out.end(), b.v.data(), b.v.data() + 3);
    out.insert(out.end(), b.omega.data(), b.omega.data() + 3);
    out.push_back(mass);
  }
  return out;
}

double Demo::penetrationAt(const std::vector<double>& poses) const {
  if (poses.size() != 7 * world_.bodies.size())
    throw std::invalid_argument("penetrationAt: " + std::to_string(poses.size()) +
                                " numbers for " + std::to_string(world_.bodies.size()) +
                                " bodies; give 7 a body (x, y, z, then the quaternion's x, y, z, w)");
  World mirror = world_;
  for (std::size_t i = 0; i < mirror.bodies.size(); ++i) {
    RigidBody& b = mirror.bodies[i];
    const double* p = &poses[7 * i];
    b.s.x = Vec3(p[0], p[1], p[2]);
    b.s.q = Quat(p[6], p[3], p[4], p[5]).normalized();
    b.updateDerived();
  }
  return deepestPenetration(mirror);
}

std::vector<std::uint8_t> Demo::flags() const {
  std::vector<std::uint8_t> out(world_.bodies.size(), 0);
  const auto* damped = dynamic_cast<const DampedIntegrationStepper*>(stepper_.get());
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (world_.bodies[i].immovable) out[i] |= kImmovable;
    if (damped == nullptr) continue;
    if (i < damped->asleep().size() && damped->asleep()[i]) out[i] |= kAsleep;
    if (i < damped->geometricallyStable().size() && damped->geometricallyStable()[i])
      out[i] |= kGeometricallyStable;
  }
  return out;
}

double Demo::largestDisplacement() const {
  double largest = 0.0;
  for (int i = 0; i < firstShot_; ++i)
    if (!world_.bodies[static_cast<std::size_t>(i)].immovable)
      largest = std::max(largest, (world_.bodies[static_cast<std::size_t>(i)].s.x -
                                   start_[static_cast<std::size_t>(i)]).norm());
  return largest;
}

std::string Demo::stateDigest() const {
  std::uint64_t hash = 14695981039346656037ULL;  // FNV-1a offset basis
  const auto add = [&](const double* values, int count) {
    unsigned char bytes[sizeof(double)];
    for (int k = 0; k < count; ++k) {
      std::memcpy(bytes, &values[k], sizeof(double));
      for (unsigned char byte : bytes) hash = (hash ^ byte) * 1099511628211ULL;  // FNV prime
    }
  };
  for (const RigidBody& b : world_.bodies) {
    add(b.s.x.data(), 3);
    add(b.s.q.coeffs().data(), 4);
    add(b.s.P.data(), 3);
    add(b.s.L.data(), 3);
  }
  static const char* kHex = "0123456789abcdef";
  std::string out(16, '0');
  for (int k = 15; k >= 0; --k, hash >>= 4) out[static_cast<std::size_t>(k)] = kHex[hash & 15];
  return out;
}

}  // namespace boxsim::web
