/// \file
/// The envelope of a pose (\thesis{§5.5}): a ball of radius r around a position together with a
/// cone of half-angle θ around an orientation. The envelope filter shows a body still while it
/// stays inside one; the trajectory measures call a body resting, and chatter detection
/// (impulse_damped/chatter_history.hpp) a body chattering, when every pose of a window stays
/// inside the envelope of the window's first pose.
#pragma once

#include "boxsim/core/math.hpp"

namespace boxsim {

/// The default envelope radius as a fraction of a body's smallest half extent: 5 %, 2.5 cm for
/// the unit cubes of the thesis' scenes. It must exceed the amplitude of chatter and stay below
/// what reads as a jump. The plain impulse step's chatter stays within about a centimetre
/// (12 mm in the standing pyramid, s5_2_chatter; under a micrometre for the die at rest,
/// s5_5_die_filtered), and a 2.5 cm step is 1/40 of a cube's edge.
inline constexpr double kEnvelopeRadiusFraction = 0.05;

/// A ball of radius r (m) and a cone of half-angle θ (rad) around a pose.
class Envelope {
 public:
  /// r, m, and θ, rad, both >= 0 (the callers check their inputs).
  Envelope(double radius, double angle);
  /// The envelope of a body of half extents h (m): r = `fraction` × its smallest half extent,
  /// θ = r / |h| (|h|, the half diagonal, is the distance of its corners from its centre), the
  /// turn that moves a corner by about r, so both bounds allow the same visible motion.
  static Envelope of(const Vec3& halfExtents, double fraction = kEnvelopeRadiusFraction);

  double radius() const { return radius_; }  ///< r, m
  double angle() const { return angle_; }    ///< θ, rad

  /// Whether the pose (x, q) lies inside the envelope around (x0, q0): |x − x0| <= r and the
  /// turn from q0 to q at most θ. The turn is compared by the sine of its half angle,
  /// |(q0* q).vec| <= sin(θ/2), which is monotonic over turns of 0 to π: a square root per call
  /// (the same bits under every C library, docs/web.md), the sine once per envelope.
  bool contains(const Vec3& x0, const Quat& q0, const Vec3& x, const Quat& q) const;

 private:
  double radius_;
  double angle_;
  double halfTurnSine_;  // sin(θ/2); above 1 when θ >= π, so every turn is inside
};

}  // namespace boxsim
