// The Open Dynamics Engine as a peer: dWorldQuickStep (projected Gauss-Seidel) at its
// defaults (20 iterations, SOR 1.3, ERP 0.2, CFM 1e-10 in double precision, auto-disable off),
// a hash space, up to 8 contacts per box pair with Coulomb friction (dContactApprox1, the
// friction pyramid) and restitution above 0.1 m/s of approach, as ODE's own demos set them.
#include <ode/ode.h>

#include <array>
#include <vector>

#include "peer_engine.hpp"

namespace boxsim::peers {

namespace {

/// dInitODE2 and dCloseODE once per process.
struct OdeLibrary {
  OdeLibrary() { dInitODE2(0); }
  ~OdeLibrary() { dCloseODE(); }
};

class OdeEngine : public PeerEngine {
 public:
  OdeEngine() {
    static OdeLibrary library;
    world_ = dWorldCreate();
    space_ = dHashSpaceCreate(nullptr);
    contacts_ = dJointGroupCreate(0);
  }
  ~OdeEngine() override {
    dJointGroupDestroy(contacts_);
    dSpaceDestroy(space_);  // destroys the geoms it holds
    dWorldDestroy(world_);  // destroys the bodies
  }
  std::string name() const override { return "ODE 0.16"; }
  std::string settings() const override {
    return "dWorldQuickStep, " + std::to_string(dWorldGetQuickStepNumIterations(world_)) +
           " iterations, hash space, dContactApprox1, auto-disable off, double precision";
  }
  void load(const PeerScene& scene) override {
    // QuickStep reorders its constraints with ODE's global random generator: seed it, so that
    // a run does not depend on the runs before it in the process.
    dRandSetSeed(1);
    dWorldSetGravity(world_, scene.gravity.x(), scene.gravity.y(), scene.gravity.z());
    restitution_ = scene.restitution;
    friction_ = scene.friction;
    boxes_ = scene.boxes;
    for (const PeerBox& box : scene.boxes) {
      const Vec3 side = 2.0 * box.halfExtents;
      const dQuaternion q = {box.q.w(), box.q.x(), box.q.y(), box.q.z()};
      dBodyID body = nullptr;
      if (!box.immovable) {
        body = dBodyCreate(world_);
        dMass mass;
        dMassSetBoxTotal(&mass, box.mass, side.x(), side.y(), side.z());
        dBodySetMass(body, &mass);
        dBodySetPosition(body, box.x.x(), box.x.y(), box.x.z());
        dBodySetQuaternion(body, q);
        dBodySetLinearVel(body, box.v.x(), box.v.y(), box.v.z());
        dBodySetAngularVel(body, box.omega.x(), box.omega.y(), box.omega.z());
        if (box.launchTime >= 0) dBodyDisable(body);
      }
      dGeomID geom = dCreateBox(box.launchTime >= 0 ? nullptr : space_, side.x(), side.y(),
                                side.z());
      if (body) {
        dGeomSetBody(geom, body);
      } else {
        dGeomSetPosition(geom, box.x.x(), box.x.y(), box.x.z());
        dGeomSetQuaternion(geom, q);
      }
      bodies_.push_back(body);
      geoms_.push_back(geom);
    }
  }
  void step(double dt, double t) override {
    for (std::size_t i = 0; i < boxes_.size(); ++i)
      if (boxes_[i].launchTime >= 0 && !dBodyIsEnabled(bodies_[i]) &&
          boxes_[i].launchTime <= t + 1e-9 * dt) {
        dSpaceAdd(space_, geoms_[i]);
        dBodyEnable(bodies_[i]);
      }
    dSpaceCollide(space_, this, &OdeEngine::nearCallback);
    dWorldQuickStep(world_, dt);
    dJointGroupEmpty(contacts_);
  }
  void read(std::vector<PeerPose>& poses) const override {
    poses.resize(geoms_.size());
    for (std::size_t i = 0; i < geoms_.size(); ++i) {
      const dReal* x = dGeomGetPosition(geoms_[i]);
      dQuaternion q;
      dGeomGetQuaternion(geoms_[i], q);
      poses[i].x = Vec3(x[0], x[1], x[2]);
      poses[i].q = Quat(q[0], q[1], q[2], q[3]);
      if (bodies_[i]) {
        const dReal* v = dBodyGetLinearVel(bodies_[i]);
        const dReal* w = dBodyGetAngularVel(bodies_[i]);
        poses[i].v = Vec3(v[0], v[1], v[2]);
        poses[i].omega = Vec3(w[0], w[1], w[2]);
      }
    }
  }

 private:
  static constexpr int kMaxContactsPerPair = 8;

  static void nearCallback(void* data, dGeomID a, dGeomID b) {
    OdeEngine& self = *static_cast<OdeEngine*>(data);
    dBodyID bodyA = dGeomGetBody(a);
    dBodyID bodyB = dGeomGetBody(b);
    if (!bodyA && !bodyB) return;
    std::array<dContact, kMaxContactsPerPair> contact{};
    const int n = dCollide(a, b, kMaxContactsPerPair, &contact[0].geom, sizeof(dContact));
    for (int i = 0; i < n; ++i) {
      dSurfaceParameters& s = contact[static_cast<std::size_t>(i)].surface;
      s.mode = dContactBounce | dContactApprox1;
      s.mu = self.friction_;
      s.bounce = self.restitution_;
      s.bounce_vel = 0.1;
      dJointID joint = dJointCreateContact(self.world_, self.contacts_, &contact[static_cast<std::size_t>(i)]);
      dJointAttach(joint, bodyA, bodyB);
    }
  }

  dWorldID world_;
  dSpaceID space_;
  dJointGroupID contacts_;
  double restitution_ = 0.9;
  double friction_ = 0.5;
  std::vector<PeerBox> boxes_;
  std::vector<dBodyID> bodies_;
  std::vector<dGeomID> geoms_;
};

}  // namespace

std::unique_ptr<PeerEngine> makeOdeEngine() { return std::make_unique<OdeEngine>(); }

}  // namespace boxsim::peers
