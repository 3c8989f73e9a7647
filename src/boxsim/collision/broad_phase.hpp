/// \file
/// Candidate pairs for the narrow phase. \thesis{§4.1}: the thesis used no spatial
/// subdivision for its small scenes; this is the all-pairs test with an axis-aligned bounding
/// box reject, in a fixed order.
#pragma once

#include <utility>
#include <vector>

#include "boxsim/collision/contact.hpp"
#include "boxsim/core/world.hpp"

namespace boxsim {

/// World-space axis-aligned bounds of a box, grown by margin (m) on every side: the centre
/// plus or minus |R| h + margin, with R the box's axes and h its half extents (m). Exact: each
/// face of the bounds touches a corner of the box when margin = 0.
void obbBounds(const Obb& box, double margin, Vec3& lo, Vec3& hi);

/// All index pairs (i, j), i < j, not both immovable, whose bounds are at most margin (m)
/// apart along every world axis (touching bounds count), in increasing (i, j) order.
/// Deterministic: nested loops over body indices, nothing hashed or sorted by address.
std::vector<std::pair<int, int>> candidatePairs(const World& world, double margin = 0.0);

/// Every pair of bodies whose manifold has at least one point (depth > -margin, m), with a and
/// b filled in, in increasing (a, b) order: collideBoxes on each of candidatePairs(world,
/// margin). \thesis{§3.2}
std::vector<ContactManifold> findContacts(const World& world, double margin = 0.0);

/// True when bodies i and j overlap with a separating-axis depth above `tolerance` (m).
bool pairIntersects(const World& world, int i, int j, double tolerance);

/// The first pair (in candidatePairs order) whose separating-axis depth exceeds `tolerance`
/// (m), or (-1, -1) when none does. A negative tolerance also reports pairs closer than
/// -tolerance.
std::pair<int, int> firstIntersectingPair(const World& world, double tolerance);

}  // namespace boxsim
