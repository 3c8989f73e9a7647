#include "boxsim/core/world.hpp"

#include <cassert>

namespace boxsim {

int World::add(const RigidBody& body, const std::string& name) {
  bodies.push_back(body);
  bodies.back().updateDerived();
  names.push_back(name);
  return static_cast<int>(bodies.size()) - 1;
}

int World::addGround(double topY, double halfSize, double halfThickness) {
  RigidBody ground = RigidBody::immovableBox(Vec3(halfSize, halfThickness, halfSize));
  ground.s.x = Vec3(0.0, topY - halfThickness, 0.0);
  groundIndex = add(ground, "ground");
  return groundIndex;
}

int World::addLaunched(const RigidBody& body, const std::string& name, double time) {
  RigidBody waiting = RigidBody::immovableBox(body.halfExtents);
  waiting.s.x = body.s.x;
  waiting.s.q = body.s.q;
  waiting.friction = body.friction;
  const int index = add(waiting, name);
  launches.push_back({index, time, body.mass, body.v, body.omega, false});
  return index;
}

int World::applyLaunches(double t) {
  int launched = 0;
  for (Launch& l : launches) {
    if (l.done || l.time > t) continue;
    const BodyState pose = bodies[l.body].s;
    RigidBody body = RigidBody::box(bodies[l.body].halfExtents, l.mass);
    body.friction = bodies[l.body].friction;  // its Coulomb friction, waiting and moving
    body.s.x = pose.x;
    body.s.q = pose.q;
    body.updateDerived();
    body.setVelocity(l.velocity);
    body.setAngularVelocity(l.angularVelocity);
    bodies[l.body] = body;
    l.done = true;
    ++launched;
  }
  return launched;
}

WorldState World::saveState() const {
  WorldState state;
  state.bodies.reserve(bodies.size());
  for (const RigidBody& b : bodies) state.bodies.push_back(b.s);
  return state;
}

void World::restoreState(const WorldState& state) {
  assert(state.bodies.size() == bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    bodies[i].s = state.bodies[i];
    bodies[i].updateDerived();
  }
}

double World::kineticEnergy() const {
  double e = 0.0;
  for (const RigidBody& b : bodies) e += b.kineticEnergy();
  return e;
}

double World::potentialEnergy() const {
  double e = 0.0;
  for (const RigidBody& b : bodies)
    if (!b.immovable) e -= b.mass * gravity.dot(b.s.x);
  return e;
}

Vec3 World::linearMomentum() const {
  Vec3 p = Vec3::Zero();
  for (const RigidBody& b : bodies)
    if (!b.immovable) p += b.s.P;
  return p;
}

int World::movableCount() const {
  int n = 0;
  for (const RigidBody& b : bodies) n += b.immovable ? 0 : 1;
  return n;
}

bool World::hasFriction() const {
  for (const RigidBody& b : bodies)
    if (!b.friction.frictionless()) return true;
  return false;
}

int addBox(World& world, const std::string& name, const Vec3& halfExtents, const Vec3& centre,
           const Quat& q) {
  RigidBody b = RigidBody::box(halfExtents, 1.0);
  b.s.x = centre;
  b.s.q = q;
  b.updateDerived();
  return world.add(b, name);
}

}  // namespace boxsim
