#include "boxsim/io/scene_builders.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "boxsim/core/random.hpp"

namespace boxsim {

namespace {
RigidBody cube(double size, double mass) {
  return RigidBody::box(Vec3::Constant(0.5 * size), mass);
}

const Vec3 kUnitHalf = Vec3::Constant(0.5);

void requirePositiveCount(int count, const char* what) {
  if (count <= 0)
    throw std::invalid_argument(std::string(what) + " must be a positive count of boxes");
}
}  // namespace

int addDie(World& world, const DieSpec& spec) {
  RigidBody b = cube(spec.size, spec.mass);
  b.s.x = spec.position;
  if (spec.tiltAxis.norm() == 0.0) throw std::invalid_argument("die tilt axis must be non-zero");
  b.s.q = axisAngleDegrees(spec.tiltAxis, spec.tiltDeg);
  b.updateDerived();
  b.setVelocity(spec.velocity);
  b.setAngularVelocity(spec.angularVelocity);
  world.add(b, "die");
  return 1;
}

int addIncline(World& world, double degrees, const Friction& friction, Vec3* down) {
  const double theta = degrees * kPi / 180.0;
  const Vec3 n(-std::sin(theta), std::cos(theta), 0.0);  // the plank's upper face normal
  const Quat q = axisAngleDegrees(Vec3::UnitZ(), degrees);
  RigidBody plank = RigidBody::immovableBox(Vec3(20.0, 0.5, 5.0));
  plank.s.x = -0.5 * n;
  plank.s.q = q;
  plank.friction = friction;
  plank.updateDerived();
  world.add(plank, "incline");
  RigidBody box = cube(1.0, 1.0);
  box.s.x = 0.5 * n;
  box.s.q = q;
  box.friction = friction;
  box.updateDerived();
  if (down) *down = -Vec3(std::cos(theta), std::sin(theta), 0.0);
  return world.add(box, "box");
}

int addTower(World& world, const TowerSpec& spec) {
  requirePositiveCount(spec.count, "tower count");
  for (int i = 0; i < spec.count; ++i) {
    RigidBody b = cube(spec.size, spec.mass);
    b.s.x = spec.origin + Vec3(0.0, (i + 0.5) * spec.size + i * spec.gap, 0.0);
    world.add(b, "tower_" + std::to_string(i));
  }
  return spec.count;
}

int addPyramid(World& world, const PyramidSpec& spec, const std::vector<PyramidBox>& omitted) {
  requirePositiveCount(spec.base, "pyramid base");
  for (const auto& [row, k] : omitted)
    if (row < 0 || row >= spec.base || k < 0 || k >= spec.base - row)
      throw std::invalid_argument("pyramid: omitted box (" + std::to_string(row) + ", " +
                                  std::to_string(k) + ") is not in a pyramid of base " +
                                  std::to_string(spec.base));
  int added = 0;
  const double pitch = spec.size + spec.gap;
  for (int row = 0; row < spec.base; ++row) {
    const int inRow = spec.base - row;
    for (int k = 0; k < inRow; ++k) {
      if (std::find(omitted.begin(), omitted.end(), PyramidBox(row, k)) != omitted.end())
        continue;
      RigidBody b = cube(spec.size, spec.mass);
      b.s.x = spec.origin + Vec3((k - 0.5 * (inRow - 1)) * pitch, (row + 0.5) * spec.size, 0.0);
      world.add(b, "pyramid_r" + std::to_string(row) + "_" + std::to_string(k));
      ++added;
    }
  }
  return added;
}

int addOneCornerOver(World& world) {
  addBox(world, "lower", kUnitHalf, Vec3(0.0, 0.5, 0.0));
  addBox(world, "upper", kUnitHalf, Vec3(0.75, 1.5, 0.75));
  return 2;
}

int addBoxOnWiderBox(World& world, const Quat& topOrientation) {
  addBox(world, "base", Vec3(1.5, 0.5, 1.5), Vec3(0.0, 0.5, 0.0));
  addBox(world, "top", kUnitHalf, Vec3(0.4, 1.5, -0.3), topOrientation);
  return 2;
}

int addBridge(World& world, bool withRightSupport) {
  addBox(world, "left", kUnitHalf, Vec3(-0.75, 0.5, 0.0));
  if (withRightSupport) addBox(world, "right", kUnitHalf, Vec3(0.75, 0.5, 0.0));
  addBox(world, "bridge", Vec3(1.0, 0.5, 0.5), Vec3(0.0, 1.5, 0.0));
  return withRightSupport ? 3 : 2;
}

int addFig6_4Staircase(World& world, double top3X) {
  addBox(world, "block0", kUnitHalf, Vec3(0.0, 0.5, 0.0));
  addBox(world, "block1", kUnitHalf, Vec3(0.15, 1.5, 0.0));
  addBox(world, "block2", kUnitHalf, Vec3(0.45, 2.5, 0.0));
  addBox(world, "block3", kUnitHalf, Vec3(top3X, 3.5, 0.0));
  return 4;
}

int addFig6_5HeavyBridge(World& world, double topMass, double armMass) {
  // RigidBody::box refuses a mass that is not finite and > 0.
  const Vec3 armHalf(1.0, 0.25, 0.5), topHalf(1.5, 0.5, 0.5);
  for (const auto& [side, sign] : {std::pair("left", -1.0), {"right", 1.0}}) {
    addBox(world, std::string("pedestal_") + side, kUnitHalf, Vec3(sign, 0.5, 0.0));
    RigidBody arm = RigidBody::box(armHalf, armMass);
    arm.s.x = Vec3(2.0 * sign, 1.25, 0.0);
    arm.updateDerived();
    world.add(arm, std::string("arm_") + side);
  }
  RigidBody top = RigidBody::box(topHalf, topMass);
  top.s.x = Vec3(0.0, 2.0, 0.0);
  top.updateDerived();
  world.add(top, "top");
  return 5;
}

int addFig5_1Row(World& world, const Vec3& origin) {
  const char* names[] = {"A", "B", "C", "D", "E"};
  const double x[] = {0.0, 1.2, 2.4, 3.6, 4.64};
  const double speed[] = {144.0, 0.0, 0.0, 6.0, 0.0};
  for (int i = 0; i < 5; ++i) {
    RigidBody b = cube(1.0, 1.0);
    b.s.x = origin + Vec3(x[i], 0.0, 0.0);
    b.updateDerived();
    b.setVelocity(Vec3(speed[i], 0.0, 0.0));
    world.add(b, names[i]);
  }
  return 5;
}

int addApproachingPairs(World& world, int count, double spacing, double gap, double speed) {
  requirePositiveCount(count, "pair count");
  for (int i = 0; i < count; ++i) {
    const double gapI = gap * (1.0 + static_cast<double>(i) / count);
    for (const int side : {-1, 1}) {
      RigidBody b = cube(1.0, 1.0);
      b.s.x = Vec3(side * 0.5 * (gapI + 1.0), 0.0, i * spacing);
      b.updateDerived();
      b.setVelocity(Vec3(-side * speed, 0.0, 0.0));
      world.add(b, "pair" + std::to_string(i) + (side < 0 ? "_left" : "_right"));
    }
  }
  return 2 * count;
}

Eigen::Vector3i clumpGrid(int count) {
  requirePositiveCount(count, "clump count");
  Eigen::Vector3i best(count, 1, 1);
  for (int nz = 1; nz * nz * nz <= count; ++nz) {
    if (count % nz != 0) continue;
    for (int ny = nz; ny * ny <= count / nz; ++ny) {
      if ((count / nz) % ny != 0) continue;
      const int nx = count / nz / ny;
      if (nx - nz < best.x() - best.z()) best = Eigen::Vector3i(nx, ny, nz);
    }
  }
  return best;
}

int addClump(World& world, const ClumpSpec& spec) {
  if (!(spec.spacing > spec.size))
    throw std::invalid_argument("clump spacing must exceed the cube size so cubes start apart");
  if (!(spec.spin >= 0.0)) throw std::invalid_argument("clump spin must be >= 0 rad/s");
  UniformRandom random(spec.seed);
  const auto uniformSpin = [&] { return spec.spin * (2.0 * random.next() - 1.0); };
  const Eigen::Vector3i n = clumpGrid(spec.count);
  int index = 0;
  for (int i = 0; i < n.x(); ++i)
    for (int j = 0; j < n.y(); ++j)
      for (int k = 0; k < n.z(); ++k) {
        const Vec3 offset = spec.spacing * Vec3(i - 0.5 * (n.x() - 1), j - 0.5 * (n.y() - 1),
                                                k - 0.5 * (n.z() - 1));
        RigidBody b = cube(spec.size, spec.mass);
        b.s.x = spec.center + offset;
        b.updateDerived();
        const Vec3 toTarget = spec.target ? Vec3(*spec.target - b.s.x) : Vec3(-offset);
        const double distance = toTarget.norm();
        if (distance > 0.0) b.setVelocity(spec.speed / distance * toTarget);
        if (spec.spin > 0.0) {
          const double wx = uniformSpin(), wy = uniformSpin(), wz = uniformSpin();
          b.setAngularVelocity(Vec3(wx, wy, wz));
        }
        world.add(b, "clump_" + std::to_string(index++));
      }
  return spec.count;
}

}  // namespace boxsim
