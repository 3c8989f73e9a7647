/// \file
/// DAMPEDINTEGRATION (\alg{A.2}, \thesis{§5.2}).
#include "boxsim/impulse_damped/damped_integration.hpp"

#include <stdexcept>

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/impulse_damped/fix_contact_constraints.hpp"
#include "boxsim/impulse_damped/impulse_pass.hpp"

namespace boxsim {

DampedIntegrationStepper::DampedIntegrationStepper(const DampedIntegrationParams& params)
    : params_(params), normals_(params.impulse.normalModel) {
  if (params.impulse.collisionIterations < 1 || params.impulse.contactIterations < 1)
    throw std::invalid_argument("damped: collision and contact iterations must be >= 1");
}

std::map<std::string, std::string> DampedIntegrationStepper::parameters() const {
  const DampingParams& d = params_.damping;
  return {{"collision_iterations", std::to_string(params_.impulse.collisionIterations)},
          {"contact_iterations", std::to_string(params_.impulse.contactIterations)},
          {"contact_normal", contactNormalModelName(params_.impulse.normalModel)},
          {"contact_margin_per_l", shortestText(params_.impulse.contactMargin)},
          {"damp", params_.damp ? "on" : "off"},
          {"fix_contact_constraints", params_.fixContactConstraints ? "on" : "off"},
          {"geometric_stability", params_.useGeometricStability ? "on" : "off"},
          {"k1_rate_per_s", shortestText(d.linearRate)},
          {"k2_rate_per_s", shortestText(d.angularRate)},
          {"k3_rate_per_s", shortestText(d.alignedAngularRate)},
          {"aligned_deg", shortestText(d.alignedAngleDeg)},
          {"eps3_g_dt", shortestText(d.verticalVelocityEps)},
          {"eps4_deg_per_s", shortestText(d.tiltRateDegPerS)},
          {"eps5_g_dt", shortestText(d.linearSmallEps)},
          {"k5", shortestText(d.linearSmallFactor)},
          {"eps6_g_dt", shortestText(d.linearZeroEps)},
          {"eps7_g_dt_per_l", shortestText(d.angularSmallEps)},
          {"k7", shortestText(d.angularSmallFactor)},
          {"eps8_g_dt_per_l", shortestText(d.angularZeroEps)},
          {"eps9_g_dt_per_l", shortestText(d.spinZeroEps)},
          {"eps10_g_dt2", shortestText(d.positionSnapEps)},
          {"eps11_g_dt2_per_l", shortestText(d.rotationSnapEps)},
          {"eps1_nudge_per_l", shortestText(params_.fixContacts.nudge)},
          {"slop_per_l", shortestText(params_.fixContacts.slop)}};
}

StepStats DampedIntegrationStepper::step(World& world, double dt) {
  StepStats stats;
  const std::size_t n = world.bodies.size();
  if (stable_.size() != n || !params_.useGeometricStability) stable_.assign(n, 0);
  const double margin = params_.impulse.contactMargin * smallestHalfExtent(world);
  // L1: RESOLVECOLLISIONS — positions predicted with gravity, impulses without.
  for (int i = 0; i < params_.impulse.collisionIterations; ++i)
    stats.events += impulsePass(world, dt, world.restitution, GravityMode::VelocityPlusGravity,
                                GravityMode::VelocityNoGravity, margin, normals_, stable_)
                        .impulses;
  // L2: RESOLVECONTACTS — restitution from -1 towards 0 (RESOLVECONTACTS L5), gravity trick.
  std::vector<char> touched(n, 0);
  const int iterations = params_.impulse.contactIterations;
  for (int i = 1; i <= iterations; ++i)
    stats.events += impulsePass(world, dt, -1.0 + static_cast<double>(i) / iterations,
                                GravityMode::VelocityPlusGravity, GravityMode::VelocityPlusGravity,
                                margin, normals_, stable_, &touched)
                        .impulses;
  // L3: IntegrateObjectVelocities.
  for (RigidBody& body : world.bodies)
    if (!body.immovable) {
      body.s.P += dt * body.mass * world.gravity;
      body.updateDerived();
    }
  // L4: DAMPENOBJECTS (its L22 integrates the positions).
  if (params_.damp) {
    dampenObjects(world, dt, touched, params_.damping);
  } else {
    predictPositions(world, dt, Vec3::Zero());
  }
  // Contacts are resolved at predicted positions, so a body at rest stops where its predicted
  // pose touches: up to g Δt² above its support. Contacts at the end of the step are gathered
  // with that gap added to the margin, or resting boxes would not count as touching.
  const double restingMargin = margin + world.gravity.norm() * dt * dt;
  // L5: FIXCONTACTCONSTRAINTS.
  if (params_.fixContactConstraints)
    fixContactConstraints(world, restingMargin, params_.fixContacts);
  // L6: SETGEOMETRICALLYSTABLE, for the next step's COLLIDE L11-L14.
  const std::vector<ContactManifold> contacts = findContacts(world, restingMargin);
  if (params_.useGeometricStability)
    stable_ = setGeometricallyStable(world, contacts, params_.geometricStability);
  normals_.endStep();
  stats.contacts = static_cast<int>(contacts.size());
  return stats;
}

}  // namespace boxsim
