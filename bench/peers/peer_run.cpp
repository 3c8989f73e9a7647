#include "peer_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <numeric>
#include <sstream>
#include <fstream>
#include <string>

#if defined(__linux__)
#include <unistd.h>
#endif

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/io/scene.hpp"

namespace boxsim::peers {

namespace {

/// Scenes with more boxes have their penetration measured every this many frames, so that the
/// harness's own measuring does not dominate its run time; timing is unaffected.
constexpr int kMeasureEveryLarge = 10;
constexpr std::size_t kLargeScene = 2000;

double kineticEnergy(const World& mirror, const std::vector<PeerPose>& poses) {
  double e = 0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const RigidBody& b = mirror.bodies[i];
    if (b.immovable) continue;
    const Vec3 inertia = boxInertiaDiagonal(b.halfExtents, b.mass);
    const Vec3 w = poses[i].q.conjugate() * poses[i].omega;  // body frame
    e += 0.5 * b.mass * poses[i].v.squaredNorm() + 0.5 * w.dot(inertia.cwiseProduct(w));
  }
  return e;
}

bool allAtRest(const World& mirror, const std::vector<PeerPose>& poses) {
  for (std::size_t i = 0; i < poses.size(); ++i)
    if (!mirror.bodies[i].immovable &&
        (poses[i].v.norm() >= kRestSpeed || poses[i].omega.norm() >= kRestSpin))
      return false;
  return true;
}

/// The deepest penetration between any two boxes (ground included) at the engine's poses.
double penetrationAt(World& mirror, const std::vector<PeerPose>& poses) {
  for (std::size_t i = 0; i < poses.size(); ++i) {
    mirror.bodies[i].s.x = poses[i].x;
    mirror.bodies[i].s.q = poses[i].q.normalized();
    mirror.bodies[i].updateDerived();
  }
  return deepestPenetration(mirror);
}

/// The time after step `last` (the last step at which the condition failed), or -1 when it
/// failed at the final step.
double heldFrom(long last, long steps, double dt) {
  return last < steps ? static_cast<double>(last) * dt : -1.0;
}

double percentile(std::vector<double> values, double fraction) {
  std::sort(values.begin(), values.end());
  const auto index = static_cast<std::size_t>(fraction * static_cast<double>(values.size()));
  return values[std::min(values.size() - 1, index)];
}

}  // namespace

std::string SceneSpec::label() const {
  char e[32];
  std::snprintf(e, sizeof e, "%g", restitution);
  return base + " e=" + e + (sleep ? "" : ", sleep off");
}

double RunResult::meanMs() const {
  return std::accumulate(stepMs.begin(), stepMs.end(), 0.0) / static_cast<double>(stepMs.size());
}
double RunResult::medianMs() const { return percentile(stepMs, 0.5); }
double RunResult::p95Ms() const { return percentile(stepMs, 0.95); }

SceneSpec sceneFromFile(const std::string& path, double seconds) {
  const World world = loadScene(path).world;
  SceneSpec spec;
  spec.base = std::filesystem::path(path).stem().string();
  spec.duration = seconds;
  spec.restitution = world.restitution;
  spec.launches = !world.launches.empty();
  spec.userFile = true;
  spec.build = [world] {
    World frictionless = world;
    for (RigidBody& body : frictionless.bodies) body.friction = {0.0, 0.0};
    return frictionless;
  };
  return spec;
}

PeerScene peerSceneOf(const SceneSpec& spec) {
  World world = spec.build();
  world.restitution = spec.restitution;
  PeerScene scene = peerSceneFromWorld(spec.label(), world, spec.duration);
  scene.sleep = spec.sleep;
  scene.friction = spec.friction;
  return scene;
}

void runRepetition(const SceneSpec& spec, PeerEngine& engine, double dt, RunResult& result) {
  PeerScene scene = peerSceneOf(spec);
  World mirror = scene.world;  // poses go in here to be measured with boxsim's own tests
  mirror.applyLaunches(std::numeric_limits<double>::infinity());
  engine.load(scene);
  result.engine = engine.name();

  const bool measure = result.repMeanMs.empty();  // the physics of the first repetition
  const long steps = std::lround(spec.duration / dt);
  const int every = scene.boxes.size() > kLargeScene ? kMeasureEveryLarge : 1;
  // The tower's top box and the die are each their scene's last body.
  const int tracked = spec.tower || spec.die ? static_cast<int>(mirror.bodies.size()) - 1 : -1;
  const Vec3 trackedStart = tracked >= 0 ? scene.boxes[static_cast<std::size_t>(tracked)].x : Vec3::Zero();
  RunMeasures m;
  m.bodies = mirror.movableCount();
  std::vector<PeerPose> poses;
  long lastMoving = 0, lastAwake = 0, measured = 0;
  double stepTotal = 0;
  for (long k = 1; k <= steps; ++k) {
    const auto start = std::chrono::steady_clock::now();
    engine.step(dt, static_cast<double>(k - 1) * dt);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    result.stepMs.push_back(ms);
    stepTotal += ms;
    if (!measure) continue;
    engine.read(poses);
    if (!allAtRest(mirror, poses)) lastMoving = k;
    if (engine.asleep() < m.bodies) lastAwake = k;
    if (k % every != 0 && k != steps) continue;
    const double depth = penetrationAt(mirror, poses);
    m.meanPenetration += depth;
    m.maxPenetration = std::max(m.maxPenetration, depth);
    m.finalPenetration = depth;
    ++measured;
  }
  result.repMeanMs.push_back(stepTotal / static_cast<double>(steps));
  if (!measure) return;
  m.meanPenetration /= static_cast<double>(std::max(1L, measured));
  m.finalKinetic = kineticEnergy(mirror, poses);
  m.asleepAtEnd = engine.asleep();
  m.allAsleepFrom = heldFrom(lastAwake, steps, dt);
  m.allAtRestFrom = heldFrom(lastMoving, steps, dt);
  if (tracked >= 0) {
    Vec3 moved = poses[static_cast<std::size_t>(tracked)].x - trackedStart;
    if (spec.die) moved.y() = 0.0;  // horizontal travel
    m.drift = moved.norm();
  }
  result.measures = m;
  result.stages = engine.stages();
  result.work = engine.work();
  result.stagedStepsMs = stepTotal;
}

void runOnce(const SceneSpec& spec, PeerEngine* engine, double dt) {
  const PeerScene scene = peerSceneOf(spec);
  if (!engine) return;
  engine->load(scene);
  const long steps = std::lround(spec.duration / dt);
  for (long k = 1; k <= steps; ++k) engine->step(dt, static_cast<double>(k - 1) * dt);
}

long peakResidentKiB() {
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key) {
    long value = -1;
    if (key == "VmHWM:" && status >> value) return value;
    status.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
  }
  return -1;
}

long peakResidentOfRun(const std::vector<std::string>& arguments) {
  const std::optional<std::string> output = outputOfRun("", arguments);
  if (!output) return -1;
  std::istringstream in(*output);
  long value = -1, last = -1;
  while (in >> value) last = value;
  return last;
}

std::optional<std::string> outputOfRun(const std::string& program,
                                       const std::vector<std::string>& arguments) {
#if defined(__linux__)
  // The program's path, then every argument quoted for the shell.
  std::string path = program;
  if (path.empty()) {
    char self[4096];
    const ssize_t length = readlink("/proc/self/exe", self, sizeof self - 1);
    if (length <= 0) return std::nullopt;
    self[length] = '\0';
    path = self;
  }
  std::string command = "'" + path + "'";
  for (const std::string& argument : arguments) command += " '" + argument + "'";
  std::fflush(nullptr);
  FILE* run = popen(command.c_str(), "r");
  if (!run) return std::nullopt;
  std::string output;
  char buffer[4096];
  for (std::size_t got; (got = std::fread(buffer, 1, sizeof buffer, run)) > 0;)
    output.append(buffer, got);
  if (pclose(run) != 0) return std::nullopt;
  return output;
#else
  (void)program;
  (void)arguments;
  return std::nullopt;
#endif
}

std::uint64_t poseDigest(const std::vector<PeerPose>& poses) {
  std::uint64_t hash = 1469598103934665603ULL;
  const auto add = [&](double value) {
    unsigned char bytes[sizeof value];
    std::memcpy(bytes, &value, sizeof value);
    for (unsigned char b : bytes) hash = (hash ^ b) * 1099511628211ULL;
  };
  for (const PeerPose& pose : poses) {
    for (int k = 0; k < 3; ++k) add(pose.x[k]);
    for (int k = 0; k < 4; ++k) add(pose.q.coeffs()[k]);
  }
  return hash;
}

}  // namespace boxsim::peers
