/// \file
/// Damped integration, the thesis' real-time technique (\thesis{§5.2}, \alg{A.2}
/// DAMPEDINTEGRATION): Guendelman et al.'s collision and contact passes with the gravity trick,
/// then gravity, damping, fixing contact constraints and classifying geometric stability.
/// The method "damped".
#pragma once

#include <vector>

#include "boxsim/core/stepper.hpp"
#include "boxsim/geometric_stability/geometric_stability.hpp"
#include "boxsim/impulse_damped/contact_normal.hpp"
#include "boxsim/impulse_damped/dampen_objects.hpp"
#include "boxsim/impulse_damped/impulse_params.hpp"

namespace boxsim {

/// Parameters of damped integration; each stage can be switched off for ablations.
struct DampedIntegrationParams {
  ImpulseParams impulse;          ///< collision and contact passes (\alg{A.2 L1-L2})
  DampingParams damping;          ///< DAMPENOBJECTS (\alg{A.2 L4})
  FixContactParams fixContacts;   ///< FIXCONTACTCONSTRAINTS (\alg{A.2 L5})
  GeometricStabilityParams geometricStability;  ///< SETGEOMETRICALLYSTABLE (\alg{A.2 L6})
  bool damp = true;               ///< run DAMPENOBJECTS' momentum damping (L1-L21)
  bool fixContactConstraints = true;   ///< run FIXCONTACTCONSTRAINTS
  bool useGeometricStability = true;   ///< run SETGEOMETRICALLYSTABLE and COLLIDE L11-L14
};

/// DAMPEDINTEGRATION(Δt) of \alg{A.2} as a Stepper ("damped").
class DampedIntegrationStepper final : public Stepper {
 public:
  /// A stepper with the given parameters; throws std::invalid_argument on iteration counts < 1.
  explicit DampedIntegrationStepper(const DampedIntegrationParams& params = {});
  std::string name() const override { return "damped"; }
  std::map<std::string, std::string> parameters() const override;
  /// \alg{A.2} DAMPEDINTEGRATION L1-L6 for one step of dt s.
  StepStats step(World& world, double dt) override;
  /// The geometric stability of each body found at the end of the last step (\alg{A.2 L6}).
  const std::vector<char>& geometricallyStable() const { return stable_; }

 private:
  DampedIntegrationParams params_;
  ContactNormalTracker normals_;
  std::vector<char> stable_;
};

}  // namespace boxsim
