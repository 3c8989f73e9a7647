/// \file
/// Shock propagation (Guendelman, Bridson and Fedkiw 2003, §7; \thesis{§2.5.2}): after contact
/// processing, the contact graph is ordered into levels from the ground up and the contacts are
/// resolved level by level, each lower level treated as infinitely heavy, so a stack settles in
/// one sweep instead of passing impulses up and down (the cost Mirtich reported, \thesis{§2.5.2}).
#pragma once

#include <vector>

#include "boxsim/core/world.hpp"
#include "boxsim/impulse_damped/contact_gathering.hpp"
#include "boxsim/impulse_damped/friction_totals.hpp"

namespace boxsim {

/// Levels of the contact graph: 0 for immovable bodies, then 1 + the smallest level of a body a
/// body touches (breadth-first from the immovable ones, in body order). Bodies the search does
/// not reach (a clump in flight) get level `bodies.size()`.
std::vector<int> contactLevels(const World& world, const std::vector<ImpulseContact>& contacts);

/// One sweep of shock propagation at the positions predicted for the end of the step
/// (x + Δt v): contacts sorted by level (then by the height of their point, then by index); a
/// contact between levels is resolved with restitution 0 and the lower body held fixed, a
/// contact within a level as usual. Positions are restored afterwards; momenta keep the change.
/// Friction draws on `totals`, the step's impulses per contact point (contactImpulse).
/// \return the number of impulses applied.
int propagateShock(World& world, double dt, double margin, ContactGathering& gathering,
                   FrictionTotals* totals = nullptr);

}  // namespace boxsim
