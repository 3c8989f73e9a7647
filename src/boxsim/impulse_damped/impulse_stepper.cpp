/// \file
/// Guendelman et al.'s impulse-based step (\thesis{§2.5.2}, \thesis{§3.3.2}).
#include "boxsim/impulse_damped/impulse_stepper.hpp"

#include <stdexcept>

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/impulse_damped/impulse_pass.hpp"
#include "boxsim/impulse_damped/shock_propagation.hpp"

namespace boxsim {

ImpulseStepper::ImpulseStepper(const ImpulseStepperParams& params)
    : params_(params), gathering_(params.impulse) {
  if (params.impulse.collisionIterations < 1 || params.impulse.contactIterations < 1)
    throw std::invalid_argument("impulse: collision and contact iterations must be >= 1");
  if (params.impulse.threads < 1)
    throw std::invalid_argument("impulse: threads must be >= 1 (1: no second thread)");
}

std::map<std::string, std::string> ImpulseStepper::parameters() const {
  std::map<std::string, std::string> parameters = impulseParameters(params_.impulse);
  parameters["shock_propagation"] = params_.shockPropagation ? "on" : "off";
  return parameters;
}

StepStats ImpulseStepper::step(World& world, double dt) {
  StepStats stats;
  // Friction's budget is the normal impulse of this step (applyPatchFriction).
  frictionTotals_.clear();
  // A frictionless world keeps no friction sums: contactImpulse would not read them.
  FrictionTotals* const totals = world.hasFriction() ? &frictionTotals_ : nullptr;
  const double margin = params_.impulse.contactMargin * smallestHalfExtent(world);
  // 1. Collisions, at positions predicted with the velocities as they are.
  for (int i = 0; i < params_.impulse.collisionIterations; ++i)
    stats.events += impulsePass(world, dt, world.restitution, GravityMode::VelocityNoGravity,
                                GravityMode::VelocityNoGravity, margin, gathering_, {}, nullptr,
                                {}, totals)
                        .impulses;
  // 2. Velocities.
  integrateVelocities(world, dt);
  // 3. Contacts, restitution ramping from -1 (no impulse) to 0 (inelastic), RESOLVECONTACTS L5.
  const int n = params_.impulse.contactIterations;
  for (int i = 1; i <= n; ++i)
    stats.events += impulsePass(world, dt, -1.0 + static_cast<double>(i) / n,
                                GravityMode::VelocityNoGravity, GravityMode::VelocityNoGravity,
                                margin, gathering_, {}, nullptr, {}, totals)
                        .impulses;
  // 4. Shock propagation.
  if (params_.shockPropagation) stats.events += propagateShock(world, dt, margin, gathering_, totals);
  // 5. Positions.
  integratePositions(world, dt, params_.impulse.integrator, poses_);
  gathering_.endStep();
  stats.contacts = static_cast<int>(findContacts(world, restingContactMargin(world, margin, dt)).size());
  return stats;
}

}  // namespace boxsim
