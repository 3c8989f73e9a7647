/// \file
/// Random perturbation of high-speed collision normals (\thesis{§4.2}).
#include "boxsim/impulse_damped/visual_plausibility.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace boxsim {

VisualPlausibility::VisualPlausibility(const PlausibilityParams& params)
    : params_(params), random_(params.seed) {
  if (!std::isfinite(params.speedThreshold) || params.speedThreshold < 0.0)
    throw std::invalid_argument(
        "plausibility: the speed threshold must be a finite number >= 0 m/s");
  if (!std::isfinite(params.maxAngleDeg) || params.maxAngleDeg < 0.0 || params.maxAngleDeg > 180.0)
    throw std::invalid_argument("plausibility: the largest angle must be in [0, 180] degrees");
}

bool VisualPlausibility::perturb(ImpulseContact& contact, double approachSpeed) {
  // §4.2: only high-velocity collisions; slow ones and contacts must be left to come to rest.
  if (!params_.enabled || !(approachSpeed > params_.speedThreshold)) return false;
  const Vec3 n = contact.normal;
  // Two unit vectors t, u completing n to an orthonormal basis, built from the world axis
  // least aligned with n so the cross product is well conditioned.
  const Vec3 absN = n.cwiseAbs();
  int least = 0;
  for (int k = 1; k < 3; ++k)
    if (absN[k] < absN[least]) least = k;
  const Vec3 t = n.cross(Vec3::Unit(least)).normalized();
  const Vec3 u = n.cross(t);
  // Uniform over the cap of half-angle θmax: cos θ uniform in [cos θmax, 1], azimuth uniform.
  const double cosMax = std::cos(params_.maxAngleDeg * kPi / 180.0);
  const double cosTheta = 1.0 - random_.next() * (1.0 - cosMax);
  const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta));
  const double phi = 2.0 * kPi * random_.next();
  contact.normal = (cosTheta * n + sinTheta * (std::cos(phi) * t + std::sin(phi) * u)).normalized();
  ++perturbations_;
  return true;
}

}  // namespace boxsim
