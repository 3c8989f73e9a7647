/// \file
/// The impulse-based time step of Guendelman, Bridson and Fedkiw ("Nonconvex Rigid Bodies with
/// Stacking", SIGGRAPH 2003, §7) as the thesis describes and first implemented it
/// (\thesis{§2.5.2}, \thesis{§3.3.2}, \thesis{§5.2}): collisions, then gravity, then contacts,
/// then shock propagation, then positions. The method "impulse".
#pragma once

#include "boxsim/core/stepper.hpp"
#include "boxsim/impulse_damped/contact_gathering.hpp"
#include "boxsim/impulse_damped/friction_totals.hpp"
#include "boxsim/impulse_damped/impulse_params.hpp"
#include "boxsim/impulse_damped/predicted_positions.hpp"

namespace boxsim {

/// ImpulseParams with every default but the gathering: every pass, \alg{A.2} as written.
inline ImpulseParams asWritten() {
  ImpulseParams params;
  params.gathering = ContactGatheringMode::EveryPass;
  return params;
}

/// Parameters of the plain impulse-based step.
struct ImpulseStepperParams {
  /// Iterations, normal model, contact margin, gathering. The plain step is the baseline the
  /// thesis measures its damping against, so it gathers contacts every pass as written
  /// (ContactGatheringMode::EveryPass); once per step is selectable. Measured on the base-10
  /// pyramid, the plain step's apex sags 2.2 mm in 5 s gathering every pass and 3 cm
  /// gathering once per step: without damping, the sequence of impulses that holds the pyramid up is
  /// sensitive to every detail of the contacts (chapters/impulse_damped/README.md).
  ImpulseParams impulse = asWritten();
  bool shockPropagation = true; ///< Guendelman et al.'s last sweep up the contact graph
};

/// Guendelman et al.'s step as a Stepper ("impulse").
class ImpulseStepper final : public Stepper {
 public:
  /// A stepper with the given parameters; throws std::invalid_argument on iteration counts < 1.
  explicit ImpulseStepper(const ImpulseStepperParams& params = {});
  std::string name() const override { return "impulse"; }
  /// Coulomb friction at every contact (applyPatchFriction).
  bool modelsFriction() const override { return true; }
  std::map<std::string, std::string> parameters() const override;
  /// One step of Δt = dt s:
  /// 1. collisions: `collisionIterations` passes at positions predicted with the current
  ///    velocities, restitution world.restitution;
  /// 2. velocities: v += g Δt;
  /// 3. contacts: `contactIterations` passes with restitution -1 + i/N (\alg{RESOLVECONTACTS L5});
  /// 4. shock propagation (when enabled);
  /// 5. positions: x += Δt v, q turned by Δt ω, the rotational energy held (integratePositions).
  StepStats step(World& world, double dt) override;

 private:
  ImpulseStepperParams params_;
  FrictionTotals frictionTotals_;  ///< the step's impulses per contact point, for friction
  ContactGathering gathering_;
  SavedPoses poses_;  ///< the poses before the step's last stage (integratePositions)
};

}  // namespace boxsim
