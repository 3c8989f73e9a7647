/// \file
/// One scene, several engines: the neutral scene description the peer harness hands to
/// boxsim, Bullet and ODE, and the small interface each engine implements so that the harness
/// times and measures them the same way.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "boxsim/core/math.hpp"
#include "boxsim/core/world.hpp"
#include "boxsim/impulse_damped/parallel_for.hpp"

namespace boxsim::peers {

/// A box as every engine receives it.
struct PeerBox {
  std::string name;                    ///< the body's name in the boxsim scene
  Vec3 halfExtents = Vec3::Constant(0.5);  ///< m
  double mass = 1.0;                   ///< kg; ignored for immovable boxes
  bool immovable = false;              ///< the ground and other scenery
  Vec3 x = Vec3::Zero();               ///< centre, m
  Quat q = Quat::Identity();           ///< orientation, body to world
  Vec3 v = Vec3::Zero();               ///< linear velocity, m/s
  Vec3 omega = Vec3::Zero();           ///< angular velocity, rad/s
  /// s; a box with a launch time >= 0 waits, immovable, at its pose until then and then moves
  /// with v and omega (the projectile of the shot pyramids). -1: moves from the start.
  double launchTime = -1.0;
};

/// A scene of the comparison.
struct PeerScene {
  std::string name;              ///< e.g. "pyramid10_shot"
  std::vector<PeerBox> boxes;    ///< in boxsim's body order
  Vec3 gravity = standardGravity();  ///< m/s^2
  double restitution = 0.9;      ///< Newtonian coefficient (boxsim's global one)
  /// Coulomb friction coefficient of every contact, for the engines that model friction.
  /// boxsim runs frictionless as the thesis (its damping stands in, \thesis{§5.2}), and with
  /// this friction as the "+friction" engines.
  double friction = 0.5;
  /// Each engine's own sleeping of bodies at rest: boxsim's computational stability
  /// (\thesis{§4.5}, damped integration only), Bullet's deactivation, ODE's auto-disable.
  bool sleep = true;
  double duration = 5.0;         ///< simulated time, s
  /// The body whose drift the table reports (the tower's top box), or -1.
  int trackedBody = -1;
  /// For the die: the body whose time of coming to rest the table reports, or -1.
  int restingBody = -1;
  /// The boxsim world the scene came from (boxsim's engine steps a copy of it).
  World world;
};

/// Builds a PeerScene from a boxsim world (bodies in order; launches as launch times).
PeerScene peerSceneFromWorld(const std::string& name, const World& world, double duration);

/// The pose and velocity of one body after a step, as an engine reports them.
struct PeerPose {
  Vec3 x = Vec3::Zero();      ///< m
  Quat q = Quat::Identity();  ///< body to world
  Vec3 v = Vec3::Zero();      ///< m/s
  Vec3 omega = Vec3::Zero();  ///< rad/s
};

/// What an engine's steps did, counted (not timed).
struct StepWork {
  /// Separating-axis tests run per pair in contact at a step's end, per step.
  double narrowPhasesPerTouchingPair = 0.0;
  /// Of those, the tests in the passes (pairs with a fast body at the passes' predicted poses).
  double passNarrowPhasesPerTouchingPair = 0.0;
  /// Tests handed back for unchanged poses (KeptNarrowPhase) per such pair per step.
  double keptPerTouchingPair = 0.0;
  /// One-axis checks that answered for a test (separatedBeyond: a pair apart along the axis of
  /// its last test), apart from the tests above, per such pair per step.
  double axisChecksPerTouchingPair = 0.0;
  double passesPerStep = 0.0;  ///< collision and contact passes per step
};

/// boxsim damped's work that threads share, measured in one untimed run on one thread (the
/// page's model of more cores).
struct SharedWork {
  double stepSeconds = 0.0;  ///< s, the run's steps, every stage (DampedStepProfile::total)
  ParallelWork work;         ///< the part of them the threads would share
  long steps = 0;            ///< the run's steps
};

/// An engine under comparison.
class PeerEngine {
 public:
  virtual ~PeerEngine() = default;
  /// Name in the table, e.g. "boxsim damped", "Bullet 3.24".
  virtual std::string name() const = 0;
  /// The settings the engine runs with, for the table's notes.
  virtual std::string settings() const = 0;
  /// Builds the engine's world from the scene; called once before the first step.
  virtual void load(const PeerScene& scene) = 0;
  /// Advances by dt (s); `t` is the time at the start of the step (for launches).
  virtual void step(double dt, double t) = 0;
  /// The state of every box, in scene order (immovable ones included).
  virtual void read(std::vector<PeerPose>& poses) const = 0;
  /// Movable boxes the engine itself holds asleep (not stepped) after the last step.
  virtual int asleep() const = 0;
  /// Seconds of the steps since load() by stage of the engine's step, largest first, for the
  /// engines that report them (boxsim damped: DampedStepProfile); empty for the others.
  virtual std::vector<std::pair<std::string, double>> stages() const { return {}; }
  /// The work of the steps since load() that had a body awake, for the engines that count it
  /// (boxsim damped: DampedStepProfile); nullopt for the others.
  virtual std::optional<StepWork> work() const { return std::nullopt; }
  /// boxsim damped with "+shared_work": what its threads would share, after a run.
  virtual std::optional<SharedWork> sharedWork() const { return std::nullopt; }
};

/// boxsim under one of its methods (techniques.hpp), e.g. "damped", or a method with a contact
/// gathering (impulse_params.hpp) after a slash, e.g. "damped/speculative". Throws
/// std::invalid_argument naming an unknown method or gathering.
std::unique_ptr<PeerEngine> makeBoxsimEngine(const std::string& method);
#ifdef BOXSIM_HAVE_BULLET
/// Bullet's btDiscreteDynamicsWorld with its default solver (sequential impulse). With `ccd`,
/// launched boxes (the pyramids' projectile) get Bullet's continuous collision detection.
std::unique_ptr<PeerEngine> makeBulletEngine(bool ccd);
#endif
#ifdef BOXSIM_HAVE_ODE
/// ODE with dWorldQuickStep and its default iterations (ode_engine.cpp states every setting).
std::unique_ptr<PeerEngine> makeOdeEngine();
#endif

}  // namespace boxsim::peers
