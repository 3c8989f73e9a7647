/// \file
/// The envelope of a pose (\thesis{§5.5}).
#include "boxsim/filtering/envelope.hpp"

#include <cmath>

namespace boxsim {

Envelope::Envelope(double radius, double angle)
    : radius_(radius), angle_(angle), halfTurnSine_(angle >= kPi ? 2.0 : std::sin(0.5 * angle)) {}

Envelope Envelope::of(const Vec3& halfExtents, double fraction) {
  const double r = fraction * halfExtents.minCoeff();
  return Envelope(r, r / halfExtents.norm());
}

bool Envelope::contains(const Vec3& x0, const Quat& q0, const Vec3& x, const Quat& q) const {
  return (x - x0).norm() <= radius_ && (q0.conjugate() * q).vec().norm() <= halfTurnSine_;
}

}  // namespace boxsim
