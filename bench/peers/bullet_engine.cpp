// Bullet Physics as a peer: btDiscreteDynamicsWorld with the dynamic AABB tree broad phase and
// the sequential impulse solver, all at Bullet 3.24's defaults: 10 solver iterations, split
// impulse on, no restitution below 0.2 m/s of approach (m_restitutionVelocityThreshold),
// deactivation of bodies resting for 2 s. Debian's Bullet is built in single precision.
#include <btBulletDynamicsCommon.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <memory>
#include <vector>

#include "peer_engine.hpp"

namespace boxsim::peers {

namespace {

btVector3 toBt(const Vec3& v) {
  return btVector3(static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()),
                   static_cast<btScalar>(v.z()));
}
Vec3 fromBt(const btVector3& v) { return Vec3(v.x(), v.y(), v.z()); }
std::string fixed2(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", value);
  return text;
}

class BulletEngine : public PeerEngine {
 public:
  explicit BulletEngine(bool ccd)
      : ccd_(ccd),
        dispatcher_(&configuration_),
        world_(&dispatcher_, &broadphase_, &solver_, &configuration_) {}
  ~BulletEngine() override {
    for (std::unique_ptr<btRigidBody>& body : bodies_)
      if (body && body->isInWorld()) world_.removeRigidBody(body.get());
  }
  std::string name() const override {
    return "Bullet " + std::to_string(BT_BULLET_VERSION / 100) + "." +
           std::to_string(BT_BULLET_VERSION % 100) + (ccd_ ? " CCD" : "");
  }
  std::string settings() const override {
    const btContactSolverInfo& info = world_.getSolverInfo();
    return "btDiscreteDynamicsWorld, btDbvtBroadphase, btSequentialImpulseConstraintSolver at "
           "its defaults (" + std::to_string(info.m_numIterations) + " iterations, split impulse " +
           (info.m_splitImpulse ? "on" : "off") + ", restitution above " +
           fixed2(info.m_restitutionVelocityThreshold) + " m/s of approach), deactivation after 2 s "
           "at rest (off in the scenes marked sleep off), single precision, stepSimulation(dt, 0): one step of dt" +
           (ccd_ ? "; CCD on launched boxes (motion threshold and swept sphere radius as "
                   "Bullet's CcdPhysicsDemo: half extent, 0.9 half extent)" : "");
  }
  void load(const PeerScene& scene) override {
    world_.setGravity(toBt(scene.gravity));
    // Bullet multiplies the two bodies' coefficients; square roots give every pair the scene's.
    const btScalar restitution = static_cast<btScalar>(std::sqrt(scene.restitution));
    const btScalar friction = static_cast<btScalar>(std::sqrt(scene.friction));
    boxes_ = scene.boxes;
    for (const PeerBox& box : scene.boxes) {
      shapes_.push_back(std::make_unique<btBoxShape>(toBt(box.halfExtents)));
      const btScalar mass = box.immovable ? 0 : static_cast<btScalar>(box.mass);
      btVector3 inertia(0, 0, 0);
      if (mass > 0) shapes_.back()->calculateLocalInertia(mass, inertia);
      btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, shapes_.back().get(), inertia);
      info.m_startWorldTransform.setOrigin(toBt(box.x));
      info.m_startWorldTransform.setRotation(
          btQuaternion(static_cast<btScalar>(box.q.x()), static_cast<btScalar>(box.q.y()),
                       static_cast<btScalar>(box.q.z()), static_cast<btScalar>(box.q.w())));
      info.m_restitution = restitution;
      info.m_friction = friction;
      bodies_.push_back(std::make_unique<btRigidBody>(info));
      btRigidBody& body = *bodies_.back();
      if (mass > 0) {
        body.setLinearVelocity(toBt(box.v));
        body.setAngularVelocity(toBt(box.omega));
        if (!scene.sleep) body.setActivationState(DISABLE_DEACTIVATION);
      }
      if (ccd_ && box.launchTime >= 0) {
        const btScalar half = static_cast<btScalar>(box.halfExtents.minCoeff());
        body.setCcdMotionThreshold(half);
        body.setCcdSweptSphereRadius(0.9f * half);
      }
      // A box waiting for its launch enters the world at its launch time.
      if (box.launchTime < 0) world_.addRigidBody(bodies_.back().get());
    }
  }
  void step(double dt, double t) override {
    for (std::size_t i = 0; i < boxes_.size(); ++i)
      if (boxes_[i].launchTime >= 0 && !bodies_[i]->isInWorld() &&
          boxes_[i].launchTime <= t + 1e-9 * dt)
        world_.addRigidBody(bodies_[i].get());
    // maxSubSteps = 0: one step of exactly dt, as every engine of the comparison takes.
    world_.stepSimulation(static_cast<btScalar>(dt), 0);
  }
  void read(std::vector<PeerPose>& poses) const override {
    poses.resize(bodies_.size());
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      const btRigidBody& b = *bodies_[i];
      const btTransform& transform = b.getCenterOfMassTransform();
      const btQuaternion r = transform.getRotation();
      poses[i].x = fromBt(transform.getOrigin());
      poses[i].q = Quat(r.w(), r.x(), r.y(), r.z());
      poses[i].v = fromBt(b.getLinearVelocity());
      poses[i].omega = fromBt(b.getAngularVelocity());
    }
  }
  int asleep() const override {
    int count = 0;
    for (const std::unique_ptr<btRigidBody>& body : bodies_)
      if (body->getInvMass() > 0 && body->isInWorld() && !body->isActive()) ++count;
    return count;
  }

 private:
  bool ccd_ = false;
  btDefaultCollisionConfiguration configuration_;
  btCollisionDispatcher dispatcher_;
  btDbvtBroadphase broadphase_;
  btSequentialImpulseConstraintSolver solver_;
  btDiscreteDynamicsWorld world_;
  std::vector<PeerBox> boxes_;
  std::vector<std::unique_ptr<btBoxShape>> shapes_;
  std::vector<std::unique_ptr<btRigidBody>> bodies_;
};

}  // namespace

std::unique_ptr<PeerEngine> makeBulletEngine(bool ccd) { return std::make_unique<BulletEngine>(ccd); }

}  // namespace boxsim::peers
