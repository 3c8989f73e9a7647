/// \file
/// FIXCONTACTCONSTRAINTS of \alg{A.2} (\thesis{§4.4}): interpenetration is removed from the
/// ground up by moving the upper body of each contact along the contact normal, positions only,
/// so no kinetic energy is added (the thesis' change to Guendelman et al.'s shock step).
#pragma once

#include <utility>
#include <vector>

#include "boxsim/collision/contact.hpp"
#include "boxsim/core/world.hpp"
#include "boxsim/impulse_damped/impulse_params.hpp"

namespace boxsim {

/// Contacts gathered with `margin` (m) are sorted by the height of their point (\alg{A.2 L1});
/// for each, the upper body (higher centre; skipped when immovable) is nudged by ε1 ℓ along the
/// lower-to-upper normal while the pair still overlaps by more than the slop (\alg{A.2 L2-L7}).
/// ℓ is the upper body's smallest half extent. Sleeping bodies stand in as immovable while this
/// runs, so they are never moved.
/// `gathered`, when given, receives the contacts found before any nudge, in findContacts order:
/// with no nudge made they are the contacts of the world as it is left, which saves the caller
/// a narrow phase.
/// \return the number of nudges made.
/// `pairs`, when given, is candidatePairs(world, margin) found by the caller (the contact
/// gathering's step candidates, ContactGathering::stepPairs), which spares the broad phase.
int fixContactConstraints(World& world, double margin, const FixContactParams& params,
                          std::vector<ContactManifold>* gathered = nullptr,
                          const std::vector<std::pair<int, int>>* pairs = nullptr);

}  // namespace boxsim
