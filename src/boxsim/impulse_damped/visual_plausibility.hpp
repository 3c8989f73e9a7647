/// \file
/// Visual plausibility (\thesis{§4.2}; Barzel, Hughes and Wood, "Plausible Motion Simulation
/// for Computer Graphics Animation", Eurographics Workshop on Computer Animation and
/// Simulation, 1996): a little randomness in high-speed collisions makes outcomes look less
/// mechanical, as a die that lands on an edge does not bounce straight up. The thesis adds it to
/// high-velocity collisions only, since randomness in slow collisions and contacts would keep
/// bodies from coming to rest. Here the normal of such a collision is turned by a small random
/// rotation drawn from a seeded Mersenne Twister (core/random.hpp), so a run is reproduced
/// exactly by its seed.
#pragma once

#include "boxsim/core/random.hpp"
#include "boxsim/impulse_damped/contact_normal.hpp"
#include "boxsim/impulse_damped/impulse_params.hpp"

namespace boxsim {

/// The random number generator and the rule that perturbs collision normals (\thesis{§4.2}).
/// Copying copies the generator's state, so a copy continues the same stream.
class VisualPlausibility {
 public:
  /// A generator seeded with params.seed (UniformRandom). Throws std::invalid_argument when
  /// speedThreshold is negative or maxAngleDeg is outside [0, 180], either not finite.
  explicit VisualPlausibility(const PlausibilityParams& params = {});

  /// Turns contact.normal (unit, from a to b) by a random rotation of at most maxAngleDeg,
  /// its direction uniform over that spherical cap, when perturbation is enabled and the
  /// bodies approach faster than speedThreshold. Draws two uniform numbers from the generator
  /// only when it perturbs, so slow collisions and contacts leave the stream untouched.
  /// \param contact       the collision; only its normal changes (stays unit length)
  /// \param approachSpeed m/s, the relative normal speed at which the bodies approach
  ///                      (positive when approaching, as approachSpeed() in impulse_pass.hpp)
  /// \return true when the normal was turned
  bool perturb(ImpulseContact& contact, double approachSpeed);

  /// The parameters in use.
  const PlausibilityParams& params() const { return params_; }
  /// Number of normals turned since construction.
  long perturbations() const { return perturbations_; }

 private:
  PlausibilityParams params_;
  UniformRandom random_;
  long perturbations_ = 0;
};

}  // namespace boxsim
