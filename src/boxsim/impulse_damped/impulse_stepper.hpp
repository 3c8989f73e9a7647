/// \file
/// The impulse-based time step of Guendelman, Bridson and Fedkiw ("Nonconvex Rigid Bodies with
/// Stacking", SIGGRAPH 2003, §7) as the thesis describes and first implemented it
/// (\thesis{§2.5.2}, \thesis{§3.3.2}, \thesis{§5.2}): collisions, then gravity, then contacts,
/// then shock propagation, then positions. The method "impulse".
#pragma once

#include "boxsim/core/stepper.hpp"
#include "boxsim/impulse_damped/contact_normal.hpp"
#include "boxsim/impulse_damped/impulse_params.hpp"

namespace boxsim {

/// Parameters of the plain impulse-based step.
struct ImpulseStepperParams {
  ImpulseParams impulse;        ///< iterations, normal model, contact margin
  bool shockPropagation = true; ///< Guendelman et al.'s last sweep up the contact graph
};

/// Guendelman et al.'s step as a Stepper ("impulse").
class ImpulseStepper final : public Stepper {
 public:
  /// A stepper with the given parameters; throws std::invalid_argument on iteration counts < 1.
  explicit ImpulseStepper(const ImpulseStepperParams& params = {});
  std::string name() const override { return "impulse"; }
  std::map<std::string, std::string> parameters() const override;
  /// One step of Δt = dt s:
  /// 1. collisions: `collisionIterations` passes at positions predicted with the current
  ///    velocities, restitution world.restitution;
  /// 2. velocities: v += g Δt;
  /// 3. contacts: `contactIterations` passes with restitution -1 + i/N (\alg{A.2 L5});
  /// 4. shock propagation (when enabled);
  /// 5. positions: x += Δt v, q turned by Δt ω.
  StepStats step(World& world, double dt) override;

 private:
  ImpulseStepperParams params_;
  ContactNormalTracker normals_;
};

}  // namespace boxsim
