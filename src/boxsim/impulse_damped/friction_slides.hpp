/// \file
/// Coulomb's cone on DAMPENOBJECTS' rests (\alg{A.2} has no friction): which frictional bodies
/// their friction cannot hold where they lie, which it holds with the load on them, and which a
/// support drags along (markFrictionSlides); dampenObjects reads the verdicts.
#pragma once

#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

#include "boxsim/collision/contact_manifold.hpp"
#include "boxsim/collision/xz_hull.hpp"
#include "boxsim/core/world.hpp"
#include "boxsim/impulse_damped/centre_over_support.hpp"

namespace boxsim {

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
  /// per body, 1 when a contact pushes it against gravity from an immovable body (the ground,
  /// a sleeping body standing in for one)
  std::vector<char> onImmovable;
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
/// Sets SupportVerdict::grounded for every held body that a contact pushes up from an immovable
/// body (the ground, a sleeping body), and, from the bottom up, for every held body that a
/// contact pushes up from a lower grounded one.
/// `lists`, when given, holds the per-body sums between calls.
/// `params` name, as for SupportTest, when two boxes lie face to face: the support points of
/// such a pair are the patch where their faces meet (levelContactPatch), whatever points the
/// narrow phase gave it, else the manifold's points.
void markFrictionSlides(const World& world, const std::vector<ContactManifold>& contacts,
                        std::vector<SupportVerdict>& support, FrictionSlideLists* lists = nullptr,
                        const SupportTestParams& params = {},
                        double dragSpeed = std::numeric_limits<double>::infinity());

}  // namespace boxsim
