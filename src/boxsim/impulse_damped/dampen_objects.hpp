/// \file
/// DAMPENOBJECTS of \alg{A.2} (\thesis{§5.3}): bodies in contact are slowed down, never sped up;
/// small velocities are shrunk and then zeroed; boxes lying nearly flat lose their vertical
/// velocity and are turned the last bit flat; then positions are integrated, and a body that
/// would barely move stays where it was.
#pragma once

#include <vector>

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
