/// \file
/// The registry of techniques: the method names the command line and the drivers accept,
/// and the stepper each one builds.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "boxsim/core/integrator.hpp"
#include "boxsim/core/stepper.hpp"
#include "boxsim/geometric_stability/geometric_stability.hpp"
#include "boxsim/impulse_damped/impulse_params.hpp"

namespace boxsim {

/// Options shared by every technique that a command line can set.
struct TechniqueOptions {
  /// Integrator between collisions (basic_colliding, analytic, the timewarps) or of the last
  /// position update (impulse, damped: semi_implicit_euler or split_rotation only, refused
  /// otherwise); empty: the technique's own default.
  std::optional<Integrator> integrator;
  /// Contact normal model of the impulse-based techniques (\thesis{§3.3.2}); empty: default.
  std::optional<ContactNormalModel> contactNormal;
  /// How the impulse-based techniques gather contacts at predicted positions
  /// (contact_gathering.hpp); empty: default (once per step).
  std::optional<ContactGatheringMode> contactGathering;
  /// Geometric stability (\thesis{§5.4}) of the analytic method (default off) and of damped
  /// integration (default thesis); under_load adds stability under load (\thesis{§6.3.1}).
  std::optional<GeometricStabilityMode> geometricStability;
  /// Computational stability (sleeping, \thesis{§4.5}) of damped integration; empty: default (on).
  std::optional<bool> sleep;
  /// Chatter detected from history (\thesis{§6.3.1}; SleepParams::chatterDetection) of damped
  /// integration; empty: default (off).
  std::optional<bool> chatterDetection;
  /// Damping of supported bodies only (DampingParams::supportedOnly) of damped integration;
  /// empty: its default (off, \alg{DAMPENOBJECTS} as written).
  std::optional<bool> dampSupportedOnly;
  /// damped: FixContactParams::stopLiftedApproach (unset: its default, on)
  std::optional<bool> fixStopApproach;
  /// Continuous collision detection for fast bodies of damped integration
  /// (continuous_collision.hpp); empty: default (off).
  std::optional<bool> continuousCollision;
  /// ImpulseParams::predictedAnchor of impulse and damped; empty: default (off).
  std::optional<bool> predictedAnchor;
  /// ImpulseParams::exactEdgePairs of impulse and damped; empty: default (off).
  std::optional<bool> exactEdgePairs;
  /// ImpulseParams::edgeCorners of impulse and damped; empty: default (off).
  std::optional<bool> edgeCorners;
  /// Collision passes damped integration may add while a pass still stops an impact
  /// (DampedIntegrationParams::impactPasses, >= 0); empty: default (0, A.2 as written).
  std::optional<int> impactPasses;
  /// Visits of a level's contacts by the shock sweep of damped integration with friction
  /// (DampedIntegrationParams::shockIterations, >= 1); empty: default (8).
  std::optional<int> shockIterations;
  /// Visual plausibility (\thesis{§4.2}) of damped integration: perturbation on with this seed;
  /// empty: off.
  std::optional<unsigned long> plausibilitySeed;
  /// Threads of the passes of the impulse-based techniques (ImpulseParams::threads, >= 1;
  /// the same trajectory for any number); empty: default (1).
  std::optional<int> threads;
};

/// The method names, in the order the thesis introduces them.
std::vector<std::string> methodNames();

/// Builds the stepper of a method. Throws std::invalid_argument naming the unknown method and
/// listing the known ones, or naming an option the method does not take.
std::unique_ptr<Stepper> makeStepper(const std::string& method, const TechniqueOptions& options = {});

}  // namespace boxsim
