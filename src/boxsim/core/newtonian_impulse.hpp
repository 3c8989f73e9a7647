/// \file
/// The Newtonian collision impulse with a coefficient of restitution between two bodies, either
/// of which may be immovable (\thesis{§3.3.2}; Witkin & Baraff, SIGGRAPH course notes
/// "Physically Based Modeling", Rigid Body Simulation, §8, eq. 8-18).
#pragma once

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

}  // namespace boxsim
