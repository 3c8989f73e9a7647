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

/// Levels of the contact graph, its working lists kept from call to call, so that a stepper that
/// sweeps every step allocates nothing once they have grown to the scene: 0 for immovable
/// bodies, then 1 + the smallest level of a body a body touches (breadth-first from the
/// immovable ones, in body order). Bodies the search does not reach (a clump in flight) get level
/// `bodies.size()`.
class ShockLevels {
 public:
  /// The levels of `contacts`, kept in levels().
  void compute(const World& world, const std::vector<ImpulseContact>& contacts);
  /// compute, then `contacts` in the sweep's order: by the higher level of their two bodies,
  /// then by the height of their point, then by their bodies' indices.
  void sort(const World& world, std::vector<ImpulseContact>& contacts);
  /// One level per body, from the last compute.
  const std::vector<int>& levels() const { return level_; }
  /// propagateShockDamped's working list, one entry per contact of a sweep: the normal impulse
  /// it has put into the contact so far (N s).
  std::vector<double>& sums() { return sums_; }
  /// propagateShockDamped's working list, one flag per contact of a sweep: the contact takes
  /// part (its pair is not settled and approaches within the sweep's bounds).
  std::vector<char>& takes() { return takes_; }

 private:
  std::vector<int> start_, fill_, neighbours_, level_, queue_;
  std::vector<double> sums_;
  std::vector<char> takes_;
};

/// One sweep of shock propagation at the positions predicted for the end of the step
/// (x + Δt v): contacts sorted by level (then by the height of their point, then by index); a
/// contact between levels is resolved with restitution 0 and the lower body held fixed, a
/// contact within a level as usual. Positions are restored afterwards; momenta keep the change.
/// Friction draws on `totals`, the step's impulses per contact point (contactImpulse).
/// \return the number of impulses applied.
int propagateShock(World& world, double dt, double margin, ContactGathering& gathering,
                   FrictionTotals* totals = nullptr);

/// Shock propagation as damped integration runs it in a world with friction, after
/// RESOLVECONTACTS (\alg{DAMPEDINTEGRATION L2}): DEVIATION(A.2, §2.5.2). The thesis keeps
/// Guendelman et al.'s sweep only as FIXCONTACTCONSTRAINTS, which moves positions and leaves
/// momenta; geometric stability (COLLIDE L11-L14) settles the aligned stacks of a frictionless
/// world. Friction holds leaning columns that neither rule reaches, and the passes (Gauss-Seidel
/// over the contacts) do not settle a column of n boxes: each box ended its step falling about
/// g Δt faster than the one under it (up to 1.2 m/s at the top of a column of seven in the 343-cube
/// pile with μ = 0.5), so it was fast, tested in every pass and never asleep, while
/// FIXCONTACTCONSTRAINTS lifted it back every step.
///
/// One sweep up the levels (ShockLevels::sort) at the positions predicted with gravity
/// (x + Δt (v + g Δt)), each contact under COLLIDE's gravity trick (\alg{COLLIDE L1-L6, L9-L14}),
/// restitution 0, the lower body of a contact between levels held fixed (a copy with zero
/// inverse mass). Within a level the contacts are visited up to `iterations` times, each
/// contact's normal impulse accumulated over the visits and kept non-negative (sequential
/// impulses, Catto, "Iterative Dynamics with Temporal Coherence", GDC 2005): a visit gives the
/// impulse that stops the contact's approach, or takes back what an earlier visit gave too
/// much, and the level is done when a visit changes nothing (a contact whose relative normal
/// velocity is within 1e-6 settledSpeed of zero is left as it is). One visit (iterations 1)
/// gives each contact its impulse once, in order: a body resting on several held supports was
/// pushed at each in turn, each push turning it, and the step tilted it into the body under it,
/// from which FIXCONTACTCONSTRAINTS lifted it: a tower of twelve layers of crossed planks built
/// touching with μ = 0.5 gained 7.7 J in 0.13 s, its top layer rising by up to 28 mm (under 0.1 J
/// with FIXCONTACTCONSTRAINTS off; DampedIntegrationParams::shockIterations).
/// The sweep applies normal impulses alone: friction in it, on any budget, held
/// every box of a tower over the box under it (five cubes on a 20° plank stood, where Coulomb
/// topples them) and slowed stacks sliding on a plank. A pair whose movable bodies are all
/// geometrically stable sits out (COLLIDE L11-L14 settles them), and so does a pair whose
/// approach under the gravity trick (approachSpeed, m/s) lies outside [settledSpeed,
/// restingSpeed]. Faster, it is a collision, which the passes resolve: held against a fixed
/// lower body, a body of a scattering heap was pushed into a third one with no pass left to
/// part them (Fig. 6.6's shot base-20 pyramid with μ = 0.5: mean penetration 2.7 mm and up to
/// 31 mm, against 1.8 and 18 mm with no sweep). Slower, the passes have settled it: a normal
/// impulse off the centre there only turned boxes the passes' friction had stopped, and kept
/// 20 boxes of the shot base-10 pyramid awake for good; and two boxes gripping each other on a
/// 30° plank parted by 3.0 mm in 2 s (0.4 mm with no sweep), the sweep's impulses not being in
/// friction's budget. Positions are restored afterwards; momenta keep the change. `stable` is
/// empty or has one flag per body (SETGEOMETRICALLYSTABLE); `levels` holds the working lists.
/// \return the number of impulses applied.
int propagateShockDamped(World& world, double dt, double margin, ContactGathering& gathering,
                         const std::vector<char>& stable, double settledSpeed,
                         double restingSpeed, ShockLevels& levels, int iterations = 1);

}  // namespace boxsim
