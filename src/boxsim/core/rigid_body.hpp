/// \file
/// A rigid box with the state vector of Witkin and Baraff's course notes, which the thesis'
/// pseudocode uses (\thesis{§3.3.2}, \thesis{§A.2}): position x, orientation q, linear
/// momentum P and angular momentum L, with v, ω, R and the world inverse inertia derived.
#pragma once

#include <cmath>

#include "boxsim/core/math.hpp"

namespace boxsim {

/// The four state variables of one body (Witkin & Baraff, "Rigid Body Simulation", §2.9).
/// Saving and restoring these is all a roll-back needs; everything else is derived.
struct BodyState {
  Vec3 x = Vec3::Zero();            ///< centre of mass, m
  Quat q = Quat::Identity();        ///< orientation, body to world, unit quaternion
  Vec3 P = Vec3::Zero();            ///< linear momentum, kg m/s
  Vec3 L = Vec3::Zero();            ///< angular momentum about the centre of mass, kg m^2/s
  /// Bitwise equality of all four state variables (for determinism tests).
  bool operator==(const BodyState& o) const {
    return x == o.x && q.coeffs() == o.q.coeffs() && P == o.P && L == o.L;
  }
};

/// Principal moments of inertia of a solid box of uniform density, kg m^2.
/// \param halfExtents half side lengths (a, b, c) in m, all > 0
/// \param mass        kg, > 0
/// \return (m/3)(b²+c², a²+c², a²+b²), the diagonal of I_body.
Vec3 boxInertiaDiagonal(const Vec3& halfExtents, double mass);

/// A body's Coulomb friction coefficients (unitless, >= 0, dynamic <= static). Both 0, the
/// default, is the thesis' frictionless contact (\thesis{§3.3.2}: "we did not model friction").
struct Friction {
  double muStatic = 0.0;   ///< μs: sticking holds while |tangential impulse| <= μs × normal
  double muDynamic = 0.0;  ///< μd: a sliding contact's friction impulse is μd × normal
  /// Whether both coefficients are zero: contact is frictionless.
  bool frictionless() const { return muStatic == 0.0 && muDynamic == 0.0; }
};

/// The friction of a contact between bodies of friction a and b: the geometric mean of each
/// coefficient, √(μa μb) (Box2D's rule; Bullet multiplies the two bodies' coefficients, so a
/// peer body given √μ matches). Equal coefficients combine to themselves; a frictionless body
/// makes its contacts frictionless.
inline Friction combinedFriction(const Friction& a, const Friction& b) {
  return {std::sqrt(a.muStatic * b.muStatic), std::sqrt(a.muDynamic * b.muDynamic)};
}

/// A rigid box. Immovable bodies (the ground) have zero inverse mass and inverse inertia,
/// so impulses and gravity leave them where they are (\thesis{§3.1}).
class RigidBody {
 public:
  /// A movable box of the given half extents (m, each > 0) and mass (kg, > 0) at rest at the
  /// origin. Throws std::invalid_argument for non-positive or non-finite input.
  static RigidBody box(const Vec3& halfExtents, double mass);
  /// An immovable box (infinite mass): the ground, walls.
  static RigidBody immovableBox(const Vec3& halfExtents);

  // --- constant quantities ---
  Vec3 halfExtents = Vec3::Constant(0.5);  ///< m
  double mass = 1.0;                       ///< kg; +inf for an immovable body
  double invMass = 1.0;                    ///< 1/kg; 0 for an immovable body
  Vec3 IbodyInvDiag = Vec3::Constant(6.0); ///< inverse principal moments, 1/(kg m^2)
  bool immovable = false;  ///< infinite mass and inertia: never moves
  Friction friction;       ///< Coulomb coefficients; frictionless by default

  // --- state (Witkin-Baraff) ---
  BodyState s;  ///< the state x, q, P, L

  // --- derived by updateDerived() ---
  Vec3 v = Vec3::Zero();      ///< linear velocity P/m, m/s
  Vec3 omega = Vec3::Zero();  ///< angular velocity Iinv L, rad/s
  Mat3 R = Mat3::Identity();  ///< rotation matrix of q; its columns are the box axes
  Mat3 Iinv = Mat3::Zero();   ///< world inverse inertia R Ibody⁻¹ Rᵀ, 1/(kg m^2)

  /// Recomputes v, ω, R and Iinv from the state. Call after every change of s.q.
  void updateDerived();
  /// Recomputes only v and ω, for a change of P or L alone (R and Iinv depend on q only);
  /// bit-identical to updateDerived() in that case, and cheaper. A change of x alone needs
  /// neither.
  void updateVelocities() {
    v = invMass * s.P;
    omega = Iinv * s.L;
  }
  /// Sets P from a velocity (m/s) and updates derived quantities. No effect if immovable.
  void setVelocity(const Vec3& velocity);
  /// Sets L from an angular velocity (rad/s) and updates derived quantities.
  void setAngularVelocity(const Vec3& angularVelocity);
  /// Velocity of the material point at world position p, m/s: v + ω × (p - x).
  Vec3 pointVelocity(const Vec3& p) const { return v + omega.cross(p - s.x); }
  /// Index (0..2) of the box axis most nearly parallel to ±y: the axis of the face a box lying
  /// on the ground rests on.
  int mostVerticalAxis() const {
    int k = 0;
    for (int i = 1; i < 3; ++i)
      if (std::abs(R(1, i)) > std::abs(R(1, k))) k = i;
    return k;
  }
  /// Kinetic energy ½ P·v + ½ L·ω, J.
  double kineticEnergy() const;
};

}  // namespace boxsim
