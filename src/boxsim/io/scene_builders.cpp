#include "boxsim/io/scene_builders.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace boxsim {

namespace {
RigidBody cube(double size, double mass) {
  return RigidBody::box(Vec3::Constant(0.5 * size), mass);
}

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

int addTower(World& world, const TowerSpec& spec) {
  requirePositiveCount(spec.count, "tower count");
  for (int i = 0; i < spec.count; ++i) {
    RigidBody b = cube(spec.size, spec.mass);
    b.s.x = spec.origin + Vec3(0.0, (i + 0.5) * spec.size + i * spec.gap, 0.0);
    world.add(b, "tower_" + std::to_string(i));
  }
  return spec.count;
}

int addPyramid(World& world, const PyramidSpec& spec) {
  requirePositiveCount(spec.base, "pyramid base");
  int added = 0;
  const double pitch = spec.size + spec.gap;
  for (int row = 0; row < spec.base; ++row) {
    const int inRow = spec.base - row;
    for (int k = 0; k < inRow; ++k) {
      RigidBody b = cube(spec.size, spec.mass);
      b.s.x = spec.origin + Vec3((k - 0.5 * (inRow - 1)) * pitch, (row + 0.5) * spec.size, 0.0);
      world.add(b, "pyramid_r" + std::to_string(row) + "_" + std::to_string(k));
      ++added;
    }
  }
  return added;
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
        const double distance = offset.norm();
        if (distance > 0.0) b.setVelocity(-spec.speed / distance * offset);
        world.add(b, "clump_" + std::to_string(index++));
      }
  return spec.count;
}

}  // namespace boxsim
