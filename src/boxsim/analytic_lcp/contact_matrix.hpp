/// \file
/// The frictionless contact LCP of a world: the matrix A and vector b relating contact force
/// magnitudes f to the relative normal accelerations a = A f + b of the contact points
/// (D. Baraff, "Fast Contact Force Computation for Nonpenetrating Rigid Bodies", SIGGRAPH 1994,
/// §2–3; Witkin and Baraff, "Physically Based Modeling", SIGGRAPH course notes, rigid body
/// dynamics part II, §8; \thesis{§2.6.1}).
///
/// Contact i joins bodies a_i and b_i at point p_i with unit normal n_i pointing from a_i to
/// b_i. Its force f_i n_i acts on b_i and −f_i n_i on a_i. With r = p − x for each body,
///
///     a_i = n_i · (p̈_b − p̈_a) + 2 ṅ_i · (ṗ_b − ṗ_a),
///
/// the second derivative of the separation. Writing J_i for the row that maps body velocities
/// to n_i · (ṗ_b − ṗ_a), that is (−n, −r_a × n) on body a and (n, r_b × n) on body b:
///
///     A = J M⁻¹ Jᵀ,   A_ij = Σ_k s_ik s_jk ( n_i·n_j / m_k + (r_ki × n_i) · I_k⁻¹ (r_kj × n_j) ),
///
/// with s = +1 on body b and −1 on body a, and immovable bodies (M⁻¹ = 0) adding nothing. A is
/// symmetric positive semidefinite. b_i holds what does not depend on f: gravity, the
/// centripetal and gyroscopic terms, and 2 ṅ_i · (ṗ_b − ṗ_a).
#pragma once

#include <vector>

#include "boxsim/analytic_lcp/lcp_solver.hpp"
#include "boxsim/collision/contact.hpp"
#include "boxsim/core/integrator.hpp"
#include "boxsim/core/world.hpp"

namespace boxsim {

/// One point of contact between two bodies.
struct PointContact {
  int a = -1;                        ///< body index
  int b = -1;                        ///< body index
  Vec3 point = Vec3::Zero();         ///< m, world
  Vec3 normal = Vec3::UnitY();       ///< unit, from a towards b
  Vec3 normalRate = Vec3::Zero();    ///< ṅ, 1/s: how the normal turns with its body
};

/// ṅ of a manifold's normal (1/s): ω × n of the body whose face gives the normal (FaceA: a,
/// FaceB: b); for an edge-edge contact, the derivative of the normalised cross product of the two
/// edges as each turns with its body (0 for near-parallel edges).
Vec3 normalRate(const World& world, const ContactManifold& m);

/// The point contacts of contact manifolds (collision/contact_manifold.hpp): every manifold
/// point becomes a contact with the manifold's normal and its normalRate.
std::vector<PointContact> pointContacts(const World& world,
                                        const std::vector<ContactManifold>& manifolds);

/// A and b of the file comment for the given contacts: A is n × n, b has n entries (m/s² per N
/// and m/s²). External forces are gravity only. Bodies flagged in `held` (empty, or one flag per
/// body) count as immovable: no velocity, no acceleration, no share of A (the geometrically
/// stable bodies of \thesis{§5.4}). Throws std::invalid_argument for a contact whose body index
/// is out of range or whose normal is not unit length (within 1e-9).
void contactMatrix(const World& world, const std::vector<PointContact>& contacts, MatX& A, VecX& b,
                   const std::vector<char>& held = {});

/// The force (N) and torque (N m, about the centre of mass) the contact forces f put on each
/// body: f_i n_i on b_i and −f_i n_i on a_i at p_i. One wrench per body of the world.
std::vector<Wrench> contactWrenches(const World& world, const std::vector<PointContact>& contacts,
                                    const VecX& f);

/// The acceleration of each body under gravity and the contact forces f (N, one per contact):
/// linear (m/s²) and angular (rad/s², ω̇ = I⁻¹ (τ + L × ω)). Immovable bodies get zeros.
void bodyAccelerations(const World& world, const std::vector<PointContact>& contacts,
                       const VecX& f, std::vector<Vec3>& linear, std::vector<Vec3>& angular);

}  // namespace boxsim
