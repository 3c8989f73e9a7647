/// \file
/// The building blocks both impulse-based techniques share: COLLIDE (\alg{A.2}) and one pass of
/// RESOLVECOLLISIONS / RESOLVECONTACTS (\alg{A.2}): move every body to its predicted position,
/// gather the pairs that touch there, put the positions back and collide each pair with the
/// lever arms found there, keeping the changed momenta (Guendelman et al. 2003, §7).
#pragma once

#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "boxsim/core/world.hpp"
#include "boxsim/impulse_damped/contact_gathering.hpp"
#include "boxsim/impulse_damped/contact_normal.hpp"
#include "boxsim/impulse_damped/friction_totals.hpp"

namespace boxsim {

/// The impulses of one contact between a and b (the contact's bodies, or stand-ins for them):
/// the Newtonian impulse at the contact's lever arms ra, rb (\alg{COLLIDE L7-L8}: one point per
/// collision); with friction, applyPatchFriction before it, on the pair's sums for the step
/// from `totals` (a budget of this impulse alone when `totals` is null: nothing before it).
/// The pair's budget grows by the normal impulse, or, when `restarted` (a geometrically stable
/// body's vertical momentum is reset after every COLLIDE, \alg{COLLIDE L11-L14}, so each
/// pass's impulse is a new estimate of the same support), becomes the largest of them. A
/// resting contact's friction (restarted, or approaching at no more than g Δt and not parting)
/// also has at least its part of the load of the body it carries (FrictionTotals::supportShare,
/// from the pass' FrictionTotals::shareWeights).
/// `supportA` / `supportB` mark a geometrically stable body under the other, which carries it
/// (applyNewtonianImpulse with supports). `sum`, when given, is the pair's entry of `totals`
/// (totals->at(contact.a, contact.b)) looked up by the caller: COLLIDE's threads must not insert.
/// \return the normal impulse, N s.
double contactImpulse(RigidBody& a, RigidBody& b, const ImpulseContact& contact, double restitution,
                      FrictionTotals* totals, bool restarted = false, bool supportA = false,
                      bool supportB = false, FrictionSum* sum = nullptr);

/// COLLIDE L6 and L10 for one body: `deltaV` (m/s) added to its velocity, unless immovable.
void addVelocity(RigidBody& body, const Vec3& deltaV);

/// COLLIDE L11-L14 for one geometrically stable body: it neither rises nor tips (its vertical
/// momentum and the x and z components of its angular momentum are zeroed).
void holdGeometricallyStable(RigidBody& body);

/// COLLIDE(collision, restitution, gravity) of \alg{A.2}: with VelocityPlusGravity both bodies'
/// velocities get g Δt added for the impulse and taken off after (\alg{COLLIDE L1-L6, L9-L10}); the
/// Newtonian impulse with `restitution` acts at the contact's lever arms ra, rb along its normal
/// (\alg{COLLIDE L7-L8}); then a geometrically stable body loses its vertical momentum and its
/// tipping angular momentum (\alg{COLLIDE L11-L14}). `stable` is empty or has one flag per body.
/// \return the impulse magnitude applied, N s (0 when the bodies separate at the point).
/// `totals` holds the step's impulses per contact point for friction (contactImpulse); it may
/// be null for frictionless worlds; `sum`, when given, is the pair's entry of it.
double collide(World& world, const ImpulseContact& contact, double restitution, GravityMode gravity,
               double dt, const std::vector<char>& stable, FrictionTotals* totals = nullptr,
               FrictionSum* sum = nullptr);

/// The relative normal speed at which the bodies of `contact` approach as COLLIDE with
/// `gravity` sees it (\alg{COLLIDE L1-L6}: under VelocityPlusGravity each movable body's
/// velocity includes the g Δt of the coming step, dt in s), m/s; positive when they approach.
double approachSpeed(const World& world, const ImpulseContact& contact, GravityMode gravity,
                     double dt);

/// The magnitude of the Newtonian impulse COLLIDE(contact, restitution, gravity) would apply
/// (\alg{COLLIDE L1-L8}), N s, computed on copies of the two bodies: the world is not
/// changed. Zero when the bodies separate at the point.
double collideImpulse(const World& world, const ImpulseContact& contact, double restitution,
                      GravityMode gravity, double dt);

/// The arguments of the COLLIDE call a pass is about to make, as a BeforeCollide hook sees them.
struct CollideCall {
  double restitution = 0.0;                              ///< unitless, COLLIDE's restitution
  GravityMode gravity = GravityMode::VelocityNoGravity;  ///< COLLIDE's gravity argument
  double dt = 0.0;                                       ///< the step, s
};

/// Called by impulsePass for each contact just before COLLIDE. It may change the contact (turn
/// its normal: visual plausibility, \thesis{§4.2}) and the mass properties of its bodies (wake
/// a sleeping body, \thesis{§4.5}); it must not move bodies or change their momenta.
using BeforeCollide = std::function<void(World&, ImpulseContact&, const CollideCall&)>;

/// What one pass found.
struct PassResult {
  int contacts = 0;  ///< pairs touching at the predicted positions
  int impulses = 0;  ///< impulses applied
  /// Whether COLLIDE (or the hook before it) changed any body's momenta or mobility, bit for
  /// bit. When it did not, the world leaves the pass as it entered it, so another pass with
  /// the same arguments would find the same contacts and change nothing either.
  bool changed = false;
  /// With island settling, whether every island is settled after the pass: the remaining
  /// passes of its loop would change nothing.
  bool settled = false;
  /// With an impact reach (impulsePass' `impactReach` > 0), the pass' impacts: contacts to
  /// which COLLIDE gave an impulse while their bodies approached (approachSpeed, after the
  /// BeforeCollide hook) faster than impactReach ℓ per Δt, ℓ the smallest half extent of the
  /// pair's smaller box (DampedIntegrationParams::impactPasses).
  int impacts = 0;
};

/// One pass of RESOLVECOLLISIONS / RESOLVECONTACTS (\alg{RESOLVECOLLISIONS L2-L6},
/// \alg{RESOLVECONTACTS L2-L6}): integrateObjectPositions (x += Δt v', q += Δt ½ ω q with v' = v +
/// g Δt under `predict` = VelocityPlusGravity), gatherCollisions (every pair closer than `margin`
/// m), revertToOriginalPositions, then COLLIDE each with `restitution` and `impulseGravity` at the
/// lever arms the gathering gives (DEVIATION(RESOLVECOLLISIONS L4-L6, RESOLVECONTACTS L4-L6): the
/// revert comes first; contact_gathering.hpp, "Where COLLIDE acts"); `gathering` does the moving
/// and gathering, exactly or to first order (contact_gathering.hpp). Bodies marked in `touched`
/// (one flag per body, or empty) get their flag set when they take part in a contact.
/// `beforeCollide`, when set, sees each contact just before its COLLIDE; `totals`, the step's
/// friction budget, goes to COLLIDE. With `settling` other than Never and a gathering that has
/// islands (OncePerStep), an island the pass left unchanged by that rule is settled: later passes
/// skip it until ContactIslands::activateAll (contact_islands.hpp; the same bits).
///
/// Threads (ImpulseParams::threads, through `gathering`): COLLIDE's loop is \alg{A.2}'s
/// Gauss-Seidel sweep, each contact seeing what the contacts before it did. Two contacts that
/// share no movable body commute exactly (each reads and writes its own two bodies and its
/// pair's friction sums; immovable bodies are only read), so the contacts are put into
/// dependency levels, each after every earlier contact that shares a movable body with it,
/// and the contacts of one level run on the threads in any order: the same bits as the loop in
/// order, for any number of threads, and no change to A.2's order. A pass runs so when its
/// levels hold ImpulseParams::parallelContacts contacts on average and no contact is between a
/// sleeper (gathering.sleepers()) and an awake body, where `beforeCollide` may wake the sleeper
/// and, through its supports, bodies of other contacts (Sleeping::wake); such a pass runs in
/// order. `beforeCollide` must change nothing for a contact between two awake bodies.
/// With `impactReach` > 0 (ℓ per Δt) the pass counts its impacts (PassResult::impacts).
PassResult impulsePass(World& world, double dt, double restitution, GravityMode predict,
                       GravityMode impulseGravity, double margin, ContactGathering& gathering,
                       const std::vector<char>& stable, std::vector<char>* touched = nullptr,
                       const BeforeCollide& beforeCollide = {}, FrictionTotals* totals = nullptr,
                       IslandSettling settling = IslandSettling::Never, double impactReach = 0.0);

/// IntegrateObjectVelocities of \alg{DAMPEDINTEGRATION L3} (and Guendelman et al.'s velocity
/// update): P += Δt m g for every movable body; positions are not touched.
void integrateVelocities(World& world, double dt);

/// The margin (m) for contacts gathered at the end of a step: `margin` plus g Δt². Contacts are
/// resolved at predicted positions, so a body at rest stops where its predicted pose touches,
/// up to g Δt² above its support; without the gap, resting boxes would not count as touching.
double restingContactMargin(const World& world, double margin, double dt);

/// The output-header entries (name, value) of the impulse-step parameters both techniques
/// share: iterations, normal model, margin, gathering and its constants.
std::map<std::string, std::string> impulseParameters(const ImpulseParams& params);

/// The smallest half extent of the movable bodies, m: the length ℓ the parameters scale with.
double smallestHalfExtent(const World& world);

}  // namespace boxsim
