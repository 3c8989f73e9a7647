/// \file
/// The impulses of one collision at all its points at once: Baraff's velocity-level LCP
/// (D. Baraff, "Analytical Methods for Dynamic Simulation of Non-penetrating Rigid Bodies",
/// SIGGRAPH 1989, §8: simultaneous collisions at several contact points), solved with the
/// contact LCP's matrix and solver (contact_matrix.hpp, lcp_solver.hpp).
///
/// A collision of two boxes touches at up to four manifold points. Newtonian impulses applied
/// point after point do not act as one collision: the first corner's impulse turns the box, the
/// next corner then approaches more slowly, and a box landing flat leaves the ground spinning
/// with less than e of its approach speed. Here the impulse magnitudes j >= 0 of all points are
/// found together. A unit impulse at point j changes the relative normal velocity at point i by
/// A_ij, the contact matrix (the same A = J M⁻¹ Jᵀ that maps forces to accelerations), so the
/// velocities after are v⁺ = v⁻ + A j, and
///
///     w = A j + b ≥ 0,   j ≥ 0,   j_i w_i = 0,   b_i = v⁻_i + e_i min(v⁻_i, 0),
///
/// asks each point to leave at least e_i times as fast as it approached (v⁺_i ≥ −e_i v⁻_i),
/// and a point that did not approach not to start approaching; an impulse acts only where the
/// bound is met exactly. A symmetric impact (a box landing flat, two boxes meeting face on face)
/// gets equal impulses at symmetric points: no spin, and the relative velocity of the centres
/// becomes −e times what it was.
#pragma once

#include "boxsim/analytic_lcp/lcp_solver.hpp"
#include "boxsim/basic_colliding/basic_colliding.hpp"

namespace boxsim {

/// Applies the impulses of `collision` (every point of one colliding pair, its normal and each
/// point's restitution e in [0, 1]) at once, as the file comment describes, solving the LCP with
/// `params` (its epsilon in m/s here: points approaching slower than it may be left so).
/// Immovable bodies do not move.
/// \return the number of points that received a nonzero impulse; 0 when no point approaches.
int applySimultaneousImpulses(World& world, const PairCollision& collision,
                              const LcpParams& params);

}  // namespace boxsim
