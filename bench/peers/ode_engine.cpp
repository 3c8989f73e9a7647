// The Open Dynamics Engine as a peer: dWorldQuickStep (projected Gauss-Seidel) with its
// default 20 iterations, SOR 1.3 and ERP 0.2; a hash space; up to 8 contacts per box pair
// (MAX_CONTACTS of ODE's box-stack demo) with Coulomb friction (dContactApprox1, the friction
// pyramid). Set as ODE's box-stack demo sets its world: global CFM 1e-5 (the single-precision
// default; ODE's manual says a larger CFM makes the system numerically better behaved than the
// double-precision 1e-10), a contact surface layer of 1 mm (contacts may sink that far before
// they push back, which the manual advises against jitter from contacts made and broken every
// step), and auto-disable (ODE's sleeping) over the average of 10 samples with ODE's default
// thresholds, when the comparison sleeps. Restitution only above 0.2 m/s of
// approach: a resting box gains g dt = 0.16 m/s of approach in one step of 1/60 s, so a lower
// threshold bounces resting contacts; 0.2 m/s is Bullet's own threshold.
#include <ode/ode.h>

#include <array>
#include <cstdio>
#include <string>
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
    // World settings (the top of the file); the scene's gravity and sleeping come at load().
    dWorldSetCFM(world_, 1e-5);
    dWorldSetContactSurfaceLayer(world_, 0.001);
    dWorldSetAutoDisableAverageSamplesCount(world_, 10);
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
           " iterations, ERP " + number(dWorldGetERP(world_)) + ", CFM " +
           number(dWorldGetCFM(world_)) + ", contact surface layer " +
           number(dWorldGetContactSurfaceLayer(world_)) + " m, hash space, up to " +
           std::to_string(kMaxContactsPerPair) + " contacts per pair, dContactApprox1, bounce "
           "above " + number(kBounceVelocity) + " m/s, auto-disable over the average of 10 samples "
           "(off in the scenes marked sleep off), double precision";
  }
  void load(const PeerScene& scene) override {
    // QuickStep reorders its constraints with ODE's global random generator: seed it, so that
    // a run does not depend on the runs before it in the process.
    dRandSetSeed(1);
    dWorldSetGravity(world_, scene.gravity.x(), scene.gravity.y(), scene.gravity.z());
    // Bodies take the world's auto-disable settings when they are created, below.
    dWorldSetAutoDisableFlag(world_, scene.sleep ? 1 : 0);
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
        // A box waiting for its launch is disabled and outside the space until then.
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
      waiting_.push_back(box.launchTime >= 0);
    }
  }
  void step(double dt, double t) override {
    // Waiting is kept apart from dBodyIsEnabled: with auto-disable a resting body is disabled
    // too, and it is in the space already.
    for (std::size_t i = 0; i < boxes_.size(); ++i)
      if (waiting_[i] && boxes_[i].launchTime <= t + 1e-9 * dt) {
        dSpaceAdd(space_, geoms_[i]);
        dBodyEnable(bodies_[i]);
        waiting_[i] = false;
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
  int asleep() const override {
    int count = 0;
    for (std::size_t i = 0; i < bodies_.size(); ++i)
      if (bodies_[i] && !waiting_[i] && !dBodyIsEnabled(bodies_[i])) ++count;
    return count;
  }

 private:
  static constexpr int kMaxContactsPerPair = 8;
  static constexpr double kBounceVelocity = 0.2;  ///< m/s, see the top of the file

  static std::string number(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
  }

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
      s.bounce_vel = kBounceVelocity;
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
  std::vector<bool> waiting_;  ///< launched boxes not yet launched
};

}  // namespace

std::unique_ptr<PeerEngine> makeOdeEngine() { return std::make_unique<OdeEngine>(); }

}  // namespace boxsim::peers
