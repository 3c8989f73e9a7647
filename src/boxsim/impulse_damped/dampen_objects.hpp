/// \file
/// DAMPENOBJECTS of \alg{A.2} (\thesis{§5.3}): bodies in contact are slowed down, never sped up;
/// small velocities are shrunk and then zeroed; boxes lying nearly flat lose their vertical
/// velocity and are turned the last bit flat; then positions are integrated, and a body that
/// would barely move stays where it was.
#pragma once

#include <limits>
#include <utility>
#include <vector>

#include "boxsim/collision/xz_hull.hpp"
#include "boxsim/core/world.hpp"
#include "boxsim/impulse_damped/centre_over_support.hpp"
#include "boxsim/impulse_damped/contact_islands.hpp"
#include "boxsim/impulse_damped/impulse_params.hpp"
#include "boxsim/impulse_damped/predicted_positions.hpp"

namespace boxsim {

/// What DAMPENOBJECTS did in one step.
struct DampingStats {
  int damped = 0;   ///< bodies that had a contact interaction and were damped
  /// Bodies kept in place by the position/rotation snap (\alg{DAMPENOBJECTS L23-L28}).
  int snapped = 0;
};

/// True when one of the box's axes lies within `angleDeg` of the y axis (\alg{DAMPENOBJECTS L3}
/// checkYAxisAlignment).
bool isYAxisAligned(const RigidBody& body, double angleDeg);

/// Turns a body about its centre by at most `maxAngle` rad towards the nearest orientation
/// with a face perpendicular to y (\alg{DAMPENOBJECTS L10} tiltTowardsYAxis).
void tiltTowardsYAxis(RigidBody& body, double maxAngle);

/// The per-body sums of markFrictionSlides, kept by a caller that asks every step so that it
/// allocates nothing once they have grown to the world.
struct FrictionSlideLists {
  std::vector<Vec3> pushed;    ///< per body, the weighted sum of its supports' normals
  std::vector<double> weight;  ///< per body, the sum of the weights
  std::vector<double> mu;      ///< per body, the weighted sum of the supports' μs
  /// A contact that pushes a movable body against gravity, made by a movable one.
  struct Carried {
    int body;             ///< the body it pushes up
    int under;            ///< the body under it
    double bears;         ///< its weight in `weight`: -n · ĝ
    std::size_t first;    ///< where its patch begins in `patches`
    std::size_t count;    ///< the patch's points
  };
  std::vector<Carried> carried;  ///< every such contact, in contact order
  /// xz, m: the patch of each carrying contact (levelContactPatch, or the manifold's points).
  std::vector<Vec2> patches;
  /// (body, xz of the point, m): the points of every contact that pushes a body against gravity.
  std::vector<std::pair<int, Vec2>> points;
  std::vector<Vec2> group;         ///< room for one body's points
  std::vector<Vec2> hull;          ///< room for one body's hull of those points
  std::vector<double> load;        ///< per body, kg: its mass and the shares pressing on it
  /// per body, kg m: those masses times where they press (its own at its centre of mass)
  std::vector<Vec3> moment;
  /// per body, while SupportVerdict::held is passed up: the part of `weight` that its movable,
  /// supported supports that are not held bear
  std::vector<double> unheldBears;
};

/// Sets SupportVerdict::slides, in `support` (one verdict per body; resized to the world's
/// bodies, new verdicts over and level), for every movable body with Coulomb friction that its
/// friction cannot hold against gravity where it lies: with N the sum of the unit normals n of
/// its contacts in `contacts` that push it against gravity (each pointing into it), each
/// weighted by its part against gravity, -n · ĝ (a side contact bears no weight), and μs the
/// static coefficients of those contacts (combinedFriction) averaged with the same weights, it
/// slides when gravity's part along the plane of N exceeds μs times its part into N, or when it
/// has no such contact or only frictionless ones (which hold nothing along them, whatever pulls
/// it: a box dragged by the friction of one sliding on it), and so does every body resting on
/// a supported one that slides.
/// Frictionless bodies are never marked: the thesis' damping stands in for their friction
/// (\thesis{§5.2}).
/// DEVIATION(DAMPENOBJECTS L6-L28): \alg{A.2} has no Coulomb friction; its rests hold a body
/// whose velocity is small, which for a box on a plank steeper than atan μ is every step (a step
/// adds g (sin θ - μ cos θ) Δt, about 3 cm/s at 35° and μ = 0.5), so friction would act as if
/// its cone had no bound. A body its friction cannot hold is not rested.
/// Sets SupportVerdict::held as well, for every movable body with Coulomb friction that is not
/// marked to slide and whose load lies over its support, seen from above (in x and z:
/// DAMPENOBJECTS reads y as up): the centre of its own weight and of the loads pressing on it
/// lies over the convex hull of the points of its contacts that push it against gravity (within
/// 1e-9 m; see `params` below), and supports that hold it bear at least half of its weight
/// (weighted by -n · ĝ as above): immovable ones, movable ones that are held, and movable ones
/// with no support of their own (in flight: nothing holds them either way). Loads are passed on
/// from the top down: a body's load (its mass and what presses on
/// it) is shared among its movable supports in proportion to what each bears, -n · ĝ, and
/// presses on each at the point of that contact's patch nearest to the load's centre (the centre itself for a body
/// on one support: a stack passes the centre of its whole load down). DAMPENOBJECTS rests
/// (L6-L21) and snaps (L23-L28) a frictional body only when it is held, then also when its own
/// centre lies past its support (SupportVerdict::over) while its load's is over it, and takes a
/// small vertical velocity from a held body as from one lying flat (L7-L9).
/// Sets SupportVerdict::dragged for every movable body with Coulomb friction that a movable body
/// it rests on, with friction between the two, slips under: at a point of their contact the
/// support's surface moves along the contact plane faster than `dragSpeed` (m/s) relative to
/// it. Its friction drags it along; the rests of its horizontal velocity and the snap would
/// hold it where it is.
/// DEVIATION(DAMPENOBJECTS L11-L15, L23-L28): the rests and the snap act on a body's velocity and
/// pose in the world, not relative to what carries it, so a box lying on one that slides away
/// under it (launched, or struck) was held still each step while Coulomb drags it at μ g: a cube
/// carried by one launched at 3 m/s along rough ground (μ 0.5) never moved, where Coulomb moves
/// it 0.115 m. Damped integration passes the speed below which the rests start to shrink a
/// velocity, ε5 g Δt (DampingParams::linearSmallEps); the default, infinity, marks none.
/// A box of a stack is not held when the one under it is not: the stack may tip. A brick lying
/// on two bricks, one of them at the edge of a hole, is held by the other, and the next step's
/// contacts decide anew if the one at the edge falls away. Passed up from any one support that
/// is not held, the hold of every brick over a hole's edge was lost, none was rested, and the
/// block over a hole punched in a wall of 200 bricks (μ 0.5, scenes/weak/wall_hit.json) leaned
/// out of its plane and fell from 6.5 s where Bullet's stands. Held by any one support that
/// holds it, the clump on the ground (μ 0.5) kept 7 of its 100 cubes awake at 30 s on one of
/// eight nudged starts; with half the weight all eight sleep whole.
/// `lists`, when given, holds the per-body sums between calls.
/// `params` name, as for SupportTest, when two boxes lie face to face: the support points of
/// such a pair are the patch where their faces meet (levelContactPatch), whatever points the
/// narrow phase gave it, else the manifold's points.
void markFrictionSlides(const World& world, const std::vector<ContactManifold>& contacts,
                        std::vector<SupportVerdict>& support, FrictionSlideLists* lists = nullptr,
                        const SupportTestParams& params = {},
                        double dragSpeed = std::numeric_limits<double>::infinity());

/// DampingParams::supportedOnly: unmarks in `touched` (one flag per body) every movable body
/// that no chain of `contacts` joins to an immovable body of `world`, so that damping leaves it
/// alone. The islands of the contacts (ContactIslands, deterministic) with every immovable body
/// as one node; O(n + m α) for n bodies and m contacts. `islands` is working room, kept by a
/// caller that asks every step.
void keepSupported(const World& world, const std::vector<ContactManifold>& contacts,
                   std::vector<char>& touched, ContactIslands& islands);

/// Scales the momenta of the bodies marked `touched` (one flag per body) as
/// \alg{DAMPENOBJECTS L1-L21}, with the thresholds of `params` turned into momenta for each body:
/// velocities in units of g Δt times the mass, angular velocities in units of g Δt / ℓ times (2/3)
/// m ℓ² (ℓ the body's smallest half extent). Never raises a body's kinetic energy. Does not move
/// bodies.
/// `support` (one verdict per body, centreOverSupport, or empty: A.2 as written) says which
/// bodies stand over their support: with DampingParams::supportTest, L6-L21 act only on those,
/// and L10 only on those that lie on top faces of one level (SupportVerdict::level). Whatever
/// DampingParams::supportTest says, L6-L21 leave alone a body marked SupportVerdict::slides,
/// and L11-L15 the horizontal velocity of one marked SupportVerdict::dragged.
void dampMomenta(World& world, double dt, const std::vector<char>& touched,
                 const DampingParams& params, DampingStats* stats = nullptr,
                 const std::vector<SupportVerdict>& support = {});

/// The whole of DAMPENOBJECTS (\alg{DAMPENOBJECTS L1-L28}): dampMomenta, then
/// integrateObjectPositions with the current velocities (\alg{DAMPENOBJECTS L22}, predictPositions
/// with `integrator`), then the snap of
/// \alg{DAMPENOBJECTS L23-L28} for bodies in contact that lie with a face perpendicular to gravity.
/// `support` as for dampMomenta; with DampingParams::supportTest the snap too holds only bodies
/// over their support, and never one marked SupportVerdict::slides or SupportVerdict::dragged.
/// `before`, when given, is the list the poses before L22 are kept in (a caller that asks every
/// step keeps its room).
DampingStats dampenObjects(World& world, double dt, const std::vector<char>& touched,
                           const DampingParams& params,
                           Integrator integrator = Integrator::SemiImplicitEuler,
                           const std::vector<SupportVerdict>& support = {},
                           SavedPoses* before = nullptr);

}  // namespace boxsim
