/// \file
/// FIXCONTACTCONSTRAINTS of \alg{A.2} (\thesis{§4.4}): interpenetration is removed from the
/// ground up by moving the upper body of each contact along the contact normal, positions only,
/// so no kinetic energy is added (the thesis' change to Guendelman et al.'s shock step).
#pragma once

#include <cstddef>
#include <tuple>
#include <utility>
#include <vector>

#include "boxsim/collision/contact.hpp"
#include "boxsim/collision/kept_narrow_phase.hpp"
#include "boxsim/core/world.hpp"
#include "boxsim/impulse_damped/impulse_params.hpp"

namespace boxsim {

/// The farthest, m, FIXCONTACTCONSTRAINTS moves `body` out of one contact in a step of `dt`
/// seconds: the larger of FixContactParams::maxNudges nudges and the distance a vertex of the
/// body can have travelled in the step, Δt (|v| + |ω| ρ) + |g| Δt² (ρ the half diagonal; v and
/// ω the velocities the positions were integrated with, g the world's gravity), so a body the
/// step carried deep into a contact can be brought out. Units of the nudge: ε1 ℓ.
///
/// DEVIATION(FIXCONTACTCONSTRAINTS L6-L7): \alg{FIXCONTACTCONSTRAINTS} nudges while the pair
/// intersects, with no bound; the guard against a contact that cannot be fixed upwards was a fixed
/// 0.1 ℓ, less than one step of fall at large Δt (g Δt² = 9.8 cm at Δt = 0.1 s, 1.5 ℓ for a 13 cm
/// plank), so a body pressed into the ground by a heavy pile sank a little further every step.
double fixLiftLimit(const RigidBody& body, const FixContactParams& params, const Vec3& gravity,
                    double dt);

/// The order of FIXCONTACTCONSTRAINTS L1, by height: (height of the manifold's centroid, m; body a;
/// body b; index of the manifold).
using FixContactOrder = std::vector<std::tuple<double, int, int, std::size_t>>;

/// Contacts gathered with `margin` (m) are sorted by the height of their point
/// (\alg{FIXCONTACTCONSTRAINTS L1}); for each, the upper body (the one the contact normal points
/// up to; by the higher centre when the normal is level; skipped when immovable) is nudged by
/// ε1 ℓ along the lower-to-upper normal while the pair still overlaps by more than the slop
/// (\alg{FIXCONTACTCONSTRAINTS L2-L7}), at most fixLiftLimit for a step of `dt` (s). ℓ is the
/// upper body's smallest half extent. Sleeping bodies stand in as immovable while this runs, so
/// they are never moved. `gathered`, when given, receives the contacts found before
/// any nudge, in findContacts order: with no nudge made they are the contacts of the world as it is
/// left, which saves the caller a narrow phase.
/// \return the number of nudges made.
/// `pairs`, when given, is candidatePairs(world, margin) found by the caller (the contact
/// gathering's step candidates, ContactGathering::stepPairs), which spares the broad phase.
/// `kept`, when given, runs every narrow phase (KeptNarrowPhase), which spares the tests of
/// pairs standing as when last tested; the same nudges.
/// `order`, when given, is the list the sort of L1 works in, kept by a caller that asks every
/// step so that it keeps its room.
int fixContactConstraints(World& world, double margin, const FixContactParams& params, double dt,
                          std::vector<ContactManifold>* gathered = nullptr,
                          const std::vector<std::pair<int, int>>* pairs = nullptr,
                          KeptNarrowPhase* kept = nullptr, FixContactOrder* order = nullptr);

}  // namespace boxsim
