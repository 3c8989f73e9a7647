/// \file
/// The Newtonian collision impulse with a coefficient of restitution between two bodies, either
/// of which may be immovable (\thesis{§3.3.2}; Witkin & Baraff, SIGGRAPH course notes
/// "Physically Based Modeling", Rigid Body Simulation, §8, eq. 8-18).
#pragma once

#include <array>

#include <Eigen/Cholesky>

#include "boxsim/core/rigid_body.hpp"

namespace boxsim {

/// Relative normal velocity of the material points of a and b at p along n (from a to b),
/// m/s: n · (v_b(p) - v_a(p)). Negative when the bodies approach.
double relativeNormalVelocity(const RigidBody& a, const RigidBody& b, const Vec3& p,
                              const Vec3& n);

/// Relative normal velocity, m/s, of the material points of a and b at the lever arms ra and
/// rb (m, from each centre of mass): n · ((v_b + ω_b × r_b) - (v_a + ω_a × r_a)). With
/// r = p - x it is the one-point form above; separate lever arms name a contact found at other
/// poses than the bodies stand at now (impulse_damped/contact_gathering.hpp).
double relativeNormalVelocity(const RigidBody& a, const RigidBody& b, const Vec3& ra,
                              const Vec3& rb, const Vec3& n);

/// The rotational part of a body's inverse mass at a contact: n · ((I⁻¹ (r × n)) × r), 1/kg,
/// for a point at offset r (m) from the centre of mass and unit normal n. Added to 1/m it is
/// the normal velocity change of that material point per unit normal impulse.
inline double rotationalInverseMass(const Mat3& Iinv, const Vec3& r, const Vec3& n) {
  return n.dot((Iinv * r.cross(n)).cross(r));
}

/// The pair's inverse mass along the unit normal n at the lever arms ra, rb (m): the change of
/// their relative normal velocity there per unit normal impulse, 1/m_a + 1/m_b plus both
/// rotational parts (rotationalInverseMass), 1/kg. The denominator of the Newtonian impulse below.
inline double pairInverseMass(const RigidBody& a, const RigidBody& b, const Vec3& ra,
                              const Vec3& rb, const Vec3& n) {
  return a.invMass + b.invMass + rotationalInverseMass(a.Iinv, ra, n) +
         rotationalInverseMass(b.Iinv, rb, n);
}

/// A copy of `body` with zero inverse mass and inertia, marked immovable: in the impulses below
/// it pushes and is not pushed (the lower levels of shock propagation, the lower body that
/// FIXCONTACTCONSTRAINTS holds).
inline RigidBody heldCopy(const RigidBody& body) {
  RigidBody held = body;
  held.invMass = 0.0;
  held.Iinv.setZero();
  held.immovable = true;
  return held;
}

/// Applies −jA n to a at lever arm ra and +jB n to b at rb (N s; n unit, from a to b), each
/// unless immovable, and updates their velocities: the step every normal impulse below ends in.
void applyNormalImpulses(RigidBody& a, RigidBody& b, const Vec3& ra, const Vec3& rb, const Vec3& n,
                         double jA, double jB);

/// Applies the frictionless Newtonian impulse j n at world point p (m) along the unit normal n
/// (pointing from a to b) when the bodies approach there, so that the relative normal velocity
/// becomes -restitution times what it was (Witkin & Baraff eq. 8-18):
/// \f[
///   j = \frac{-(1 + e)\, v^-}{\frac{1}{m_a} + \frac{1}{m_b}
///       + \hat n \cdot \left(I_a^{-1}(r_a \times \hat n)\right) \times r_a
///       + \hat n \cdot \left(I_b^{-1}(r_b \times \hat n)\right) \times r_b}
/// \f]
/// with \f$v^- = \hat n \cdot (\dot p_b - \dot p_a)\f$ and \f$r_{a,b} = p - x_{a,b}\f$.
/// \param restitution e in [0, 1]; 0 perfectly inelastic, 1 elastic
/// \return the impulse magnitude j >= 0 (N s); 0 when the bodies separate or both are
///         immovable. b receives +j n, a receives -j n.
double applyNewtonianImpulse(RigidBody& a, RigidBody& b, const Vec3& p, const Vec3& n,
                             double restitution);

/// The same impulse with a lever arm per body: a receives -j n at x_a + ra, b receives +j n at
/// x_b + rb (ra, rb in m), and j makes the relative normal velocity of those two material points
/// -restitution times what it was. As each body's velocity change is measured at the point its
/// impulse acts on, the kinetic energy ½ P·v + ½ L·ω of the pair changes by
/// ½ j (1 - e) v⁻ <= 0 for e in [-1, 1], whatever the lever arms: an impulse never adds energy.
/// The one-point form is this with r_{a,b} = p - x_{a,b}, bit for bit.
/// \return j >= 0, N s, as above.
double applyNewtonianImpulse(RigidBody& a, RigidBody& b, const Vec3& ra, const Vec3& rb,
                             const Vec3& n, double restitution);

/// The impulse above where `supportA` / `supportB` marks a geometrically stable body that
/// carries the other (\thesis{§5.4}; COLLIDE L11-L14 then reset its vertical momentum): when
/// that support is lighter than the body it carries, the carried body takes the impulse it would
/// get from a support as heavy as itself, j' = -(1 + e) v⁻ / (k + k_s m_s / m) (k, k_s: the
/// carried body's and the support's inverse mass along n at the contact, as pairInverseMass
/// sums them; m, m_s their masses), while the support takes the impulse above with its own mass.
/// A support as heavy as the body it carries, or heavier, changes nothing (the same bits).
/// \return the larger of the two impulses, N s (the contact's normal load).
/// DEVIATION(COLLIDE L8): as written, j takes the support's whole inverse mass and L11-L14 then
/// take its vertical part back, so each pass stops a share m_s / (m + m_s) of the carried body's
/// approach. Between equal masses that is half, and the passes stop it; on a support a thousand
/// times lighter a pass stops a thousandth, FIXCONTACTCONSTRAINTS holds the body in place while
/// its velocity grows, and it is thrown up: a 1000 kg cube dropped on a 1 kg one gained energy
/// from 24.5 kJ to 109.6 kJ in 20 s and never slept (a 100 kg cube on a 0.1 kg one: 2.9 to 7.7 kJ).
/// With the support taken as heavy as its load, the passes stop the carried body as between equal
/// masses, and the energy never exceeds its start. Taking the support as immovable for the
/// carried body, or as L11-L14 leave it for both, stopped the rise too, but changed every stack
/// of equal boxes (14 of 16 reference scenes), and held for both bodies it pressed supports out
/// sideways (a box of the 343-cube pile at e = 0.9 with μ = 0.5 was thrown off the 40 m ground).
double applyNewtonianImpulse(RigidBody& a, RigidBody& b, const Vec3& ra, const Vec3& rb,
                             const Vec3& n, double restitution, bool supportA, bool supportB);

/// The five friction rows of a contact (applyPatchFriction) with the pair's inverse mass in
/// them and its inverse, and what they were computed from. Within a step a body's inverse inertia
/// changes only with its mobility, and a cached contact keeps its lever arms from pass to pass,
/// so the rows are rebuilt only when one of their inputs differs bitwise: the same bits as
/// building them in every pass, without the 5×5 products and the inversion.
struct FrictionRows {
  using Mat35 = Eigen::Matrix<double, 3, 5>;  ///< a 3×5 matrix: the rows' angular Jacobians
  using Mat5 = Eigen::Matrix<double, 5, 5>;   ///< a 5×5 matrix: the rows' inverse mass
  Vec3 ra = Vec3::Zero();            ///< input: lever arm of a, m
  Vec3 rb = Vec3::Zero();            ///< input: lever arm of b, m
  Vec3 n = Vec3::Zero();             ///< input: unit normal, a to b
  Mat3 IinvA = Mat3::Zero();         ///< input: world inverse inertia of a, 1/(kg m²)
  Mat3 IinvB = Mat3::Zero();         ///< input: world inverse inertia of b, 1/(kg m²)
  double invMassA = 0.0;             ///< input: 1/m of a, 1/kg
  double invMassB = 0.0;             ///< input: 1/m of b, 1/kg
  bool torsion = false;              ///< input: the spin row is taken (patch radius > 0)
  bool tipping = false;              ///< input: the tipping rows are taken (2 or more points)
  bool valid = false;                ///< the fields below were computed from the inputs above
  Vec3 t1 = Vec3::Zero();            ///< first tangent, n.unitOrthogonal()
  Vec3 t2 = Vec3::Zero();            ///< second tangent, n × t1
  Mat35 Ga = Mat35::Zero();          ///< angular Jacobian of the rows on a (columns: rows)
  Mat35 Gb = Mat35::Zero();          ///< angular Jacobian of the rows on b
  Mat5 W = Mat5::Zero();             ///< the pair's inverse mass in the rows
  /// W⁻¹, from W's Cholesky factor C (W = C Cᵀ) as C⁻ᵀ C⁻¹, each entry a fixed sequence of
  /// plain operations (applyPatchFriction's sticking impulse is W⁻¹ times the slip: a product
  /// in every pass where two triangular solves took twice the time, the rows being kept for
  /// most passes of a step).
  Mat5 Winv = Mat5::Zero();
  bool factorised = false;           ///< W's Cholesky factor exists (W positive definite)
  double normW = 0.0;                ///< W.norm(), the scale of the energy guard
  /// The tipping rows' own block of W factorised (the couple that stops the tipping under
  /// sliding friction), formed on first use.
  Eigen::LLT<Eigen::Matrix2d> tippingLlt;
  bool tippingFactorised = false;    ///< tippingLlt holds the block of the W above
  /// The sliding and spin rows' own block of W factorised (the friction that stops the sliding
  /// under a couple the patch holds back), formed on first use.
  Eigen::LLT<Eigen::Matrix3d> slidingLlt;
  bool slidingFactorised = false;    ///< slidingLlt holds the block of the W above
};

/// What a contact has received so far in a step: the budget and the state of its friction.
struct FrictionSum {
  double normal = 0.0;             ///< N s, the normal impulses
  Vec3 tangential = Vec3::Zero();  ///< N s, the friction impulses (world vector)
  double torsional = 0.0;          ///< N m s, the friction's angular impulse about the normal
  Vec3 couple = Vec3::Zero();      ///< N m s, the tipping couple (in the contact plane)
  FrictionRows rows;               ///< the rows of its last friction impulse
};

/// The contact patch of a face contact, about its centroid.
struct ContactPatch {
  /// m, the manifold's points minus the centroid, the first `count`, in order around the patch.
  std::array<Vec3, 4> offsets{};
  /// The manifold point (ContactManifold::points index) each offset was made from.
  std::array<int, 4> pointOf{};
  int count = 0;                  ///< 0 to 4; 2 is a line of contact
  double radius = 0.0;            ///< m, mean distance from the centroid (contactPatchRadius)
};

/// Coulomb friction of a contact patch at its centroid, its budget the normal impulse the
/// contact has received so far in the step (Catto, "Iterative Dynamics with Temporal
/// Coherence", GDC 2005: accumulated impulses, clamped).
///
/// Five rows of the pair's relative motion at the centroid are stopped together: sliding along
/// the two tangents, spin about the normal n, and tipping about the two tangents (a 5×5 solve
/// of the pair's inverse mass in those rows). The impulses found are added to the sums of
/// `sum` and the sums are limited:
/// - friction: (J_t, τ / ρ) within μs N (sticking), else scaled onto the ellipse of μd N
///   (sliding); the ellipse is the limit surface of a uniformly pressed patch as Goyal, Ruina
///   and Papadopoulos (1991) approximate it, ρ = patch.radius (0: no spin row);
/// - tipping: a normal impulse N acting at a point p of the patch instead of its centroid is
///   the same impulse plus the couple N p × n; the couple's centre of pressure n × couple / N
///   is kept within the patch polygon (scaled towards the centroid until it is; a line of
///   contact holds only along itself); where it is held back, the sliding and spin rows are
///   solved again under the couple held and limited as above (a box tipping over an edge keeps
///   the friction that holds the edge).
/// N = sum.normal. The change of the sums acts on the bodies (b: +J at x_b + rb and the angular
/// impulse +A; a the opposite) unless it would raise the pair's kinetic energy, and `sum` is
/// updated. A contact with no budget (N = 0) whose sums are still zero gets no friction and
/// nothing is computed: Coulomb's limit would take every row back to zero.
/// DEVIATION(COLLIDE L7, Guendelman et al. 2003 §7): the thesis acts at one point per collision
/// and is frictionless; Guendelman et al. apply a coupled sticking-or-sliding impulse at each
/// point. At one point a friction impulse at the centre of a box's base has a moment no single
/// normal impulse balances (a cube on a 20° incline with μ = 0.5 rocked and crept at 44 mm/s),
/// and the single impulses of A.2's restitution ramp (RESOLVECONTACTS L5) cannot each pay for
/// the friction a step needs; point by point the impulses disturb each other (the same cube
/// crept at 15 mm/s). The patch's couple stands in for the shift of pressure across the base,
/// and the budget is the step's normal impulse; the normal impulses stay the thesis'
/// frictionless ones at the centroid.
void applyPatchFriction(RigidBody& a, RigidBody& b, const Vec3& ra, const Vec3& rb, const Vec3& n,
                        const Friction& friction, const ContactPatch& patch, FrictionSum& sum);

}  // namespace boxsim
