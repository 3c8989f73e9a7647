/// \file
/// Named builders for the thesis' scenes: the die (\thesis{§4.2}), a tower, the pyramid of
/// Fig. 6.6 (one box deep: our reading of the figure) and the clump of Fig. 6.7 (\thesis{§6.1});
/// sizes, masses and speeds are ours where the thesis gives none. Each adds bodies to a world
/// and returns how many it added; all bodies are cubes of one size and mass (\thesis{§3.1}).
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "boxsim/core/world.hpp"

namespace boxsim {

/// A cube dropped with a tilt, the die of \thesis{§4.2}.
struct DieSpec {
  double size = 1.0;                  ///< edge length, m
  double mass = 1.0;                  ///< kg
  Vec3 position = Vec3(0.0, 2.0, 0.0);  ///< initial centre, m
  double tiltDeg = 10.0;              ///< tilt angle, degrees
  Vec3 tiltAxis = Vec3(1.0, 0.0, 1.0);  ///< tilt axis (normalised by the builder)
  Vec3 velocity = Vec3::Zero();       ///< m/s
  Vec3 angularVelocity = Vec3::Zero();  ///< rad/s
};

/// `count` cubes stacked on the plane y = baseY, centred on (x, z) = (origin.x, origin.z),
/// with a vertical gap (m) between neighbours.
struct TowerSpec {
  int count = 10;  ///< number of cubes, >= 1
  double size = 1.0;   ///< m
  double mass = 1.0;   ///< kg
  Vec3 origin = Vec3::Zero();  ///< bottom centre of the tower, m
  double gap = 0.0;    ///< m, >= 0
};

/// A one-box-deep pyramid: rows of base, base-1, ..., 1 cubes in the x-y plane, resting on
/// y = origin.y, centred on origin.x, at depth origin.z (\thesis{Fig. 6.6}).
struct PyramidSpec {
  int base = 10;  ///< cubes in the bottom row, >= 1
  double size = 1.0;   ///< m
  double mass = 1.0;   ///< kg
  Vec3 origin = Vec3::Zero();  ///< bottom centre, m
  double gap = 0.0;    ///< horizontal gap between neighbours in a row, m, >= 0
};

/// `count` cubes on a regular grid of the given spacing centred on `center`, each moving at
/// `speed` towards `target`, the grid's centre unless given (\thesis{Fig. 6.7}: "an initial
/// velocity towards the origin"; a cube standing on the target does not move). The grid is nx × ny × nz = count with the
/// three as close to equal as count allows (100 = 5 × 5 × 4, 1000 = 10³). With `spin` > 0 each
/// cube also spins, every component of its angular velocity drawn uniformly from [−spin, spin]
/// by the Mersenne Twister of core/random.hpp seeded with `seed` (the same scene for the same seed), so that a clump
/// dropped close to the ground tumbles into a heap instead of landing as one block.
struct ClumpSpec {
  int count = 100;  ///< number of cubes, >= 1
  double size = 1.0;     ///< m
  double mass = 1.0;     ///< kg
  double spacing = 2.0;  ///< centre-to-centre distance, m, > size
  Vec3 center = Vec3(0.0, 20.0, 0.0);  ///< m
  double speed = 5.0;    ///< m/s towards the target
  double spin = 0.0;     ///< rad/s, largest component of a cube's random angular velocity, >= 0
  unsigned long seed = 1;  ///< seed of the spins' random generator
  /// m: the point the cubes move towards; unset, the grid's centre (last, so that specs written
  /// field by field in order keep their meaning)
  std::optional<Vec3> target = std::nullopt;
};

/// Adds the die; returns 1. Throws std::invalid_argument on non-positive size or mass.
int addDie(World& world, const DieSpec& spec);
/// Adds the tower; returns spec.count.
int addTower(World& world, const TowerSpec& spec);
/// A box of a pyramid: its row and its index in the row, both from 0 at the bottom left.
using PyramidBox = std::pair<int, int>;

/// Adds the pyramid without the boxes in `omitted` ({0, 4} is the bottom centre of a base of
/// 9, \thesis{Fig. 5.6}); returns the boxes added, base (base + 1) / 2 when none is omitted.
/// Throws std::invalid_argument naming an omitted box that is not in the pyramid.
int addPyramid(World& world, const PyramidSpec& spec, const std::vector<PyramidBox>& omitted = {});
/// Adds the clump; returns spec.count.
int addClump(World& world, const ClumpSpec& spec);

/// \thesis{Fig. 5.3}: a cube "lower" on the ground and a cube "upper" on it, shifted by ¾ of
/// its size along x and z, so only one of its bottom corners lies over the lower cube: not
/// geometrically stable. Unit cubes of 1 kg resting on the plane y = 0. Returns 2.
int addOneCornerOver(World& world);
/// \thesis{Fig. 5.4}: a 3 × 1 × 3 m box "base" on the plane y = 0 and a unit cube "top" wholly
/// on it, centred over (0.4, −0.3), turned by topOrientation about its centre (keep its bottom
/// face down). Both stable. 1 kg each. Returns 2.
int addBoxOnWiderBox(World& world, const Quat& topOrientation = Quat::Identity());
/// \thesis{Fig. 5.5}: unit cubes "left" and (withRightSupport) "right" on the plane y = 0,
/// 0.5 m apart, and a 2 × 1 × 1 m box "bridge" lying across them, two of its bottom corners on
/// each. Stable with both supports, not with the left alone. 1 kg each. Returns the count.
int addBridge(World& world, bool withRightSupport = true);
/// \thesis{Fig. 6.4} as we read it, "a series of blocks [that] could be treated as one heavier
/// object": unit cubes "block0" on the plane y = 0 at x = 0 and "block1" to "block3" stacked on
/// it, each shifted along +x from the one below (centres at x = 0.15, 0.45 and 0.8 m, or
/// x3 = top3X), so the top block reaches 0.8 m past the bottom one's edge. None but block0
/// passes §5.4's rule (each overhangs its support); as long as the blocks above every level,
/// taken as one body, have their centre of mass over that level's support (0.625 over
/// [−0.05, 0.65] and 0.467 over [−0.35, 0.5] with the defaults; top3X > 0.85 breaks the
/// first), they are stable under load. 1 kg each. Returns 4.
int addFig6_4Staircase(World& world, double top3X = 0.8);
/// \thesis{Fig. 6.5} as we read it, "a heavy block resting across two separate supports":
/// unit cubes "pedestal_left" and "pedestal_right" on the plane y = 0 at x = ∓1; on each a
/// 2 × 0.5 × 1 m arm ("arm_left", "arm_right", armMass kg) centred at x = ∓2, which rests on
/// its pedestal over x ∈ [1, 1.5] (mirrored) with its centre 0.5 m beyond the pedestal's
/// outer edge, so it would tip outward alone; and a 3 × 1 × 1 m block "top" of topMass kg
/// across both arms (on x ∈ [1, 1.5] of each). The top's weight on the arms' inner ends holds
/// them when topMass/2 × 0.5 m ≥ armMass × 0.5 m: stable under load for topMass ≥ 2 armMass,
/// derived by hand (moments about the pedestal's outer edge). Returns 5; throws
/// std::invalid_argument on a mass that is not finite and > 0.
int addFig6_5HeavyBridge(World& world, double topMass, double armMass = 1.0);

/// Beyond the thesis (Coulomb friction, impulse chapter): an immovable 40 × 1 × 10 m plank
/// "incline" through the origin tilted by `degrees` about z (rising towards +x), and a unit
/// cube "box" of 1 kg resting on it at rest, both with the given friction. Gravity is the
/// world's, along −y. Returns the box's index; `down` receives the unit vector down the slope.
int addIncline(World& world, double degrees, const Friction& friction, Vec3* down = nullptr);

/// \thesis{Fig. 5.1}: five unit cubes of 1 kg named "A" to "E" in a row along x at
/// x = 0, 1.2, 2.4, 3.6, 4.64 m (y = origin.y; gaps 0.2, 0.2, 0.2, 0.04 m), shifted by origin.
/// A moves right at 144 m/s: in a 1/60 s frame it ends past B, overlapping C. D moves right at
/// 6 m/s and ends overlapping E. Meant for gravity 0 and restitution 1, so the true sequence
/// is A→B→C→D→E, a Newton's cradle. Returns 5.
int addFig5_1Row(World& world, const Vec3& origin = Vec3::Zero());

/// `count` independent head-on collisions (\thesis{§2.4.3}: events far apart, where the
/// timewarp rewinds only the bodies involved): pair i is two unit cubes of 1 kg at
/// z = i · spacing, faces g_i = gap (1 + i / count) m apart along x, approaching at `speed`
/// m/s each. With gravity 0, pair i's cubes meet after g_i / (2 speed) s: every pair at its
/// own time, between gap / (2 speed) and twice that. Names "pair<i>_left", "pair<i>_right".
/// Returns 2 count; throws std::invalid_argument on count < 1.
int addApproachingPairs(World& world, int count, double spacing = 10.0, double gap = 0.2,
                        double speed = 3.0);

/// The grid dimensions the clump builder uses for `count` cubes (nx >= ny >= nz, product
/// == count, as close to a cube as possible).
Eigen::Vector3i clumpGrid(int count);

}  // namespace boxsim
