/// \file
/// The world: bodies (the ground among them, as an immovable box), gravity, the global
/// coefficient of restitution and the broad phase that finds candidate pairs. Saving and
/// restoring the whole state is the roll-back the basic colliding technique needs
/// (\thesis{§2.1}).
#pragma once

#include <string>
#include <vector>

#include "boxsim/core/rigid_body.hpp"

namespace boxsim {

/// The state of every body at one instant, in body order. Restoring it is a roll-back.
struct WorldState {
  std::vector<BodyState> bodies;  ///< one state per body, in body order
  /// Bitwise equality of every body state.
  bool operator==(const WorldState& o) const { return bodies == o.bodies; }
};

/// A body that enters the simulation at a given time, as the projectile shot into the pyramid
/// of \thesis{Fig. 6.6}: until then it waits, immovable, at its launch pose.
struct Launch {
  int body = -1;                        ///< index of the body
  double time = 0.0;                    ///< s
  double mass = 1.0;                    ///< kg, restored at launch
  Vec3 velocity = Vec3::Zero();         ///< m/s at launch
  Vec3 angularVelocity = Vec3::Zero();  ///< rad/s at launch
  bool done = false;                    ///< set once launched
};

/// Which broad phase finds the candidate pairs of the narrow phase (collision/broad_phase.hpp,
/// whose broadPhaseName and parseBroadPhase give the names "all_pairs" and "sweep_and_prune").
/// Both return the same pairs in the same order, so the choice changes only speed, never a
/// trajectory. \thesis{§4.1}
enum class BroadPhase {
  /// Every pair tested, O(n²) for n bodies: what \thesis{§4.1} did for its small scenes.
  AllPairs,
  /// Sort and sweep along one axis (or a uniform grid for many bodies), O(n log n + k) for k
  /// pairs (sweepAndPrunePairs in collision/sweep_and_prune.hpp).
  SweepAndPrune,
};

/// Bodies, gravity, global material constants and the broad phase. Body indices are stable: a
/// body's index is its identity everywhere (contacts, recorder columns, output files).
class World {
 public:
  std::vector<RigidBody> bodies;      ///< all bodies, movable and immovable
  std::vector<std::string> names;     ///< one name per body, for messages and output headers
  Vec3 gravity = standardGravity();   ///< m/s^2
  /// Global Newtonian coefficient of restitution, 0.9 as in \thesis{§3.3.2}.
  double restitution = 0.9;
  /// Index of the ground body, or -1 when the scene has none.
  int groundIndex = -1;
  /// The broad phase every query on this world uses (candidatePairs, findContacts,
  /// refindContacts, firstIntersectingPair, deepestPenetration, the impulse techniques' contact
  /// gathering), as a collision world owns its broad phase in established engines (Bullet's
  /// btCollisionWorld takes a btBroadphaseInterface). Sweep and prune by default; all pairs is
  /// the thesis' own test and the reference the sweep is checked against. Not part of
  /// WorldState: saving and restoring keep it.
  BroadPhase broadPhase = BroadPhase::SweepAndPrune;

  /// Bodies waiting to be launched, in the order they were added.
  std::vector<Launch> launches;

  /// Adds a body with a name; returns its index.
  int add(const RigidBody& body, const std::string& name);
  /// Adds the ground: an immovable box whose top face is the plane y = topY (m), of the
  /// given horizontal half size (m) and thickness (m). Returns its index.
  int addGround(double topY = 0.0, double halfSize = 50.0, double halfThickness = 0.5);

  /// Adds a movable box that waits, immovable, at its pose until `time` (s), then moves with
  /// the given velocities. It keeps its friction, waiting and moving. Returns its index.
  int addLaunched(const RigidBody& body, const std::string& name, double time);
  /// Launches every waiting body whose time is <= t (s): it gets its mass and inertia back and
  /// its launch velocities, and keeps the friction it waited with. Returns how many were
  /// launched.
  int applyLaunches(double t);

  /// Copies out the state of every body.
  WorldState saveState() const;
  /// Restores a state saved from this world (same body count) and updates derived values.
  void restoreState(const WorldState& state);

  /// Total kinetic energy, J.
  double kineticEnergy() const;
  /// Total gravitational potential energy -m g·x of the movable bodies, J (zero at x = 0).
  double potentialEnergy() const;
  /// Total linear momentum of the movable bodies, kg m/s.
  Vec3 linearMomentum() const;
  /// Number of movable bodies.
  int movableCount() const;
  /// Whether some body has Coulomb friction (RigidBody::friction not frictionless).
  bool hasFriction() const;
};

/// Adds a box of 1 kg named `name` with the given half extents (m) at `centre` (m), turned by
/// q; returns its index. The building block of the scenes of io/scene_builders.hpp, of the
/// sticking scenes and of the tests' own.
int addBox(World& world, const std::string& name, const Vec3& halfExtents, const Vec3& centre,
           const Quat& q = Quat::Identity());

}  // namespace boxsim
