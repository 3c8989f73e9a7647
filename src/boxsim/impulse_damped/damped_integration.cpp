/// \file
/// DAMPEDINTEGRATION (\alg{A.2}, \thesis{§5.2}), with sleeping bodies (\thesis{§4.5}, in
/// sleeping.cpp) and perturbed high-speed collisions (\thesis{§4.2}).
#include "boxsim/impulse_damped/damped_integration.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/impulse_damped/centre_over_support.hpp"
#include "boxsim/impulse_damped/fix_contact_constraints.hpp"

namespace boxsim {

DampedIntegrationStepper::DampedIntegrationStepper(const DampedIntegrationParams& params)
    : params_(params), gathering_(params.impulse), plausibility_(params.plausibility) {
  if (params.impulse.collisionIterations < 1 || params.impulse.contactIterations < 1)
    throw std::invalid_argument("damped: collision and contact iterations must be >= 1");
  if (params.impulse.threads < 1)
    throw std::invalid_argument("damped: threads must be >= 1 (1: no second thread)");
  if (params.impactPasses < 0 || !(params.impactReach > 0.0) || !std::isfinite(params.impactReach))
    throw std::invalid_argument(
        "damped: impact passes must be >= 0 and the impact reach a finite number > 0 (units of l)");
  if (params.shockIterations < 1)
    throw std::invalid_argument("damped: shock iterations must be >= 1 (1: one visit of each contact)");
  if (!(params.fixContacts.stopLiftedOver >= 0.0) || !std::isfinite(params.fixContacts.stopLiftedOver))
    throw std::invalid_argument(
        "damped: the lift FIXCONTACTCONSTRAINTS' stop begins at must be a finite number >= 0 "
        "(units of g dt^2; 4 by default)");
  if (params.continuousCollision.maxSubsteps < 1 ||
      !(params.continuousCollision.fastReach > 0.0))
    throw std::invalid_argument(
        "damped: continuous collision needs maxSubsteps >= 1 and fastReach > 0 (units of l)");
  // Assigned after the iteration check rather than initialised before it: with several invalid
  // parameters, the iteration counts are the ones reported.
  sleeping_ = Sleeping(params.sleep, params.fixContacts.slop);
}

std::map<std::string, std::string> DampedIntegrationStepper::parameters() const {
  const DampingParams& d = params_.damping;
  const SleepParams& s = params_.sleep;
  const PlausibilityParams& p = params_.plausibility;
  std::map<std::string, std::string> parameters = impulseParameters(params_.impulse);
  parameters.merge(std::map<std::string, std::string>{
      {"damp", params_.damp ? "on" : "off"},
      {"damp_colliding_bodies", params_.dampCollidingBodies ? "on" : "off"},
      {"friction_shock_propagation", params_.shockPropagation ? "on" : "off"},
      {"shock_settled_speed_g_dt", shortestText(params_.shockSettledSpeed)},
      {"shock_resting_speed_g_dt", shortestText(params_.shockRestingSpeed)},
      {"shock_iterations", std::to_string(params_.shockIterations)},
      {"fix_contact_constraints", params_.fixContactConstraints ? "on" : "off"},
      {"geometric_stability", !params_.useGeometricStability            ? "off"
                                  : params_.geometricStability.underLoad ? "under_load"
                                                                         : "thesis"},
      {"k1_rate_per_s", shortestText(d.linearRate)},
      {"k2_rate_per_s", shortestText(d.angularRate)},
      {"k3_rate_per_s", shortestText(d.alignedAngularRate)},
      {"aligned_deg", shortestText(d.alignedAngleDeg)},
      {"eps3_g_dt", shortestText(d.verticalVelocityEps)},
      {"damp_support_test", d.supportTest ? "on" : "off"},
      {"damp_supported_only", d.supportedOnly ? "on" : "off"},
      {"eps4_deg_per_s", shortestText(d.tiltRateDegPerS)},
      {"eps5_g_dt", shortestText(d.linearSmallEps)},
      {"k5", shortestText(d.linearSmallFactor)},
      {"eps6_g_dt", shortestText(d.linearZeroEps)},
      {"eps7_g_dt_per_l", shortestText(d.angularSmallEps)},
      {"k7", shortestText(d.angularSmallFactor)},
      {"eps8_g_dt_per_l", shortestText(d.angularZeroEps)},
      {"eps9_g_dt_per_l", shortestText(d.spinZeroEps)},
      {"eps9_either_sign", d.spinZeroSymmetric ? "on" : "off"},
      {"eps10_g_dt2", shortestText(d.positionSnapEps)},
      {"eps11_g_dt2_per_lmax", shortestText(d.rotationSnapEps)},
      {"damp_rest_held", d.restHeld ? "on" : "off"},
      {"damp_rest_grounded", d.restGrounded ? "on" : "off"},
      {"eps1_nudge_per_l", shortestText(params_.fixContacts.nudge)},
      {"slop_per_l", shortestText(params_.fixContacts.slop)},
      {"fix_side_share_deg", shortestText(params_.fixContacts.sideShareAngleDeg)},
      {"fix_stop_lifted_approach", params_.fixContacts.stopLiftedApproach ? "on" : "off"},
      {"fix_stop_lifted_over_g_dt2", shortestText(params_.fixContacts.stopLiftedOver)},
      {"sleep", s.enabled ? "on" : "off"},
      {"sleep_time_s", shortestText(s.timeToSleep)},
      {"sleep_still_by", s.stillByPose ? "pose" : "pose_and_momenta"},
      {"wake_speed_g_dt", shortestText(s.wakeSpeed)},
      {"wake_impulse_g_dt", shortestText(s.wakeImpulse)},
      {"support_normal_y", shortestText(s.supportNormalY)},
      {"chatter_detection", s.chatterDetection ? "on" : "off"},
      {"chatter_envelope_per_l", shortestText(s.chatterEnvelope)},
      {"plausibility", p.enabled ? "on" : "off"},
      {"plausibility_speed_m_per_s", shortestText(p.speedThreshold)},
      {"plausibility_max_deg", shortestText(p.maxAngleDeg)},
      {"seed", std::to_string(p.seed)},
      {"continuous_collision", params_.continuousCollision.enabled ? "on" : "off"},
      {"ccd_fast_reach_per_l", shortestText(params_.continuousCollision.fastReach)},
      {"ccd_max_substeps", std::to_string(params_.continuousCollision.maxSubsteps)},
      {"impact_passes", std::to_string(params_.impactPasses)},
      {"impact_reach_per_l", shortestText(params_.impactReach)}});
  return parameters;
}

StepStats DampedIntegrationStepper::step(World& world, double dt) {
  // A.2 takes +y as up: a world whose gravity points elsewhere is stepped turned so that it
  // points along -y (core/gravity_frame.hpp), and handed back turned back.
  if (gravityPointsDown(world.gravity)) return stepUpright(world, dt);
  World& upright = gravityFrame_.enter(world);
  const StepStats stats = stepUpright(upright, dt);
  gravityFrame_.leave(world);
  return stats;
}

StepStats DampedIntegrationStepper::stepUpright(World& world, double dt) {
  const ContinuousCollisionParams& ccd = params_.continuousCollision;
  if (!ccd.enabled) return advance(world, dt);
  // DEVIATION(A.2, §3.2): a step in which a fast body would reach another body is split at
  // that time of impact, so the collision passes predict it touching, not past it: A.2 sees
  // contacts only at the predicted pose, and a unit cube at 150 m/s passes a 1 m ground there.
  // A piece ends twice the resting-contact margin short of the impact: within it, the flat
  // cube would count as resting on the ground (SETGEOMETRICALLYSTABLE), and COLLIDE L11-L14
  // would take its vertical momentum instead of bouncing it.
  const double stopGap = 2.0 * restingContactMargin(
                                   world, params_.impulse.contactMargin * smallestHalfExtent(world), dt);
  const double shortest = dt / ccd.maxSubsteps;
  StepStats stats;
  double remaining = dt;
  for (int piece = 1; remaining > 0.0; ++piece) {
    double h = remaining;
    if (piece < ccd.maxSubsteps)
      h = std::max(shortest, firstTimeOfImpact(world, remaining, stopGap, ccd));
    // The last piece takes what is left, so the pieces add up to dt exactly.
    if (h >= remaining - 1e-9 * dt) h = remaining;
    stats += advance(world, h);
    remaining -= h;
  }
  return stats;
}

namespace {
/// True when `world` has as many bodies as `poses` and each body's x and q are bitwise those.
bool posesUnchanged(const World& world, const std::vector<std::pair<Vec3, Quat>>& poses) {
  if (poses.size() != world.bodies.size()) return false;
  for (std::size_t i = 0; i < poses.size(); ++i)
    if (world.bodies[i].s.x != poses[i].first ||
        world.bodies[i].s.q.coeffs() != poses[i].second.coeffs())
      return false;
  return true;
}

/// Adds the wall-clock time of each stage of a step to its slot of a profile, if there is one.
class StageClock {
 public:
  explicit StageClock(DampedStepProfile* profile) : profile_(profile) {
    if (!profile_) return;
    ++profile_->steps;
    mark_ = Clock::now();
  }
  /// The time since the last lap (or the start) goes to `slot`.
  void lap(double DampedStepProfile::*slot) {
    if (!profile_) return;
    const Clock::time_point now = Clock::now();
    profile_->*slot += std::chrono::duration<double>(now - mark_).count();
    mark_ = now;
  }

 private:
  using Clock = std::chrono::steady_clock;
  DampedStepProfile* profile_;
  Clock::time_point mark_;
};
}  // namespace

StepStats DampedIntegrationStepper::advance(World& world, double dt) {
  StepStats stats;
  StageClock clock(profile_);
  const std::size_t n = world.bodies.size();
  if (stable_.size() != n || !params_.useGeometricStability) stable_.assign(n, 0);
  // ℓ before sleeping bodies stand in as immovable, which would hide them from it.
  const double margin = params_.impulse.contactMargin * smallestHalfExtent(world);
  // The guard comes first: begin already turns sleeping bodies into immovable stand-ins, and
  // their real mass properties must come back whatever happens after.
  const Sleeping::RestoreOnExit restoreOnExit(sleeping_, world);
  // §4.5: with every movable body asleep nothing can happen; the step costs nothing.
  const bool awake = sleeping_.begin(world);
  gathering_.setSleepers(params_.sleep.enabled ? &sleeping_.asleep() : nullptr);
  clock.lap(&DampedStepProfile::sleeping);
  if (!awake) {
    stats.sleeping = sleeping_.asleepCount();
    stats.contacts = sleeping_.restingContacts();
    return stats;
  }
  // Friction's budget is the normal impulse of this step (applyPatchFriction).
  frictionTotals_.clear();
  const bool friction = world.hasFriction();
  // A frictionless world keeps no friction sums: contactImpulse would not read them.
  FrictionTotals* const totals = friction ? &frictionTotals_ : nullptr;
  // DAMPENOBJECTS reads the contacts the step starts from (the support test, friction's slides,
  // the supported bodies): they are the last step's, kept with the poses they are for.
  const bool startingContacts =
      params_.damping.supportTest || friction || params_.damping.supportedOnly;
  // The narrow phases so far, for the profile's count of this step's.
  const long passTestsBefore = gathering_.passNarrowPhases();
  const long axisChecksBefore = gathering_.passAxisChecks() + gathering_.kept().axisChecks();
  const long testsBefore = gathering_.kept().tests() + passTestsBefore;
  const long reusesBefore = gathering_.kept().reuses();
  // Bodies that take part in a contact (or, with dampCollidingBodies, a collision) this step.
  std::vector<char>& touched = touched_;
  touched.assign(n, 0);
  // With a predicted anchor, the bodies touching another where the last step left them (its
  // FIXCONTACTCONSTRAINTS found their contacts at these very poses) are those anchored.
  if (params_.impulse.predictedAnchor) {
    touchingAtStart_.assign(n, 0);
    for (const ContactManifold& m : lastContacts_)
      if (m.count > 0 && m.a >= 0 && m.b >= 0 && static_cast<std::size_t>(m.a) < n &&
          static_cast<std::size_t>(m.b) < n)
        touchingAtStart_[static_cast<std::size_t>(m.a)] =
            touchingAtStart_[static_cast<std::size_t>(m.b)] = 1;
    gathering_.setTouching(&touchingAtStart_);
  }
  // The contacts of the step's start, found before the first pass would find them.
  gathering_.beginStep(world, dt, GravityMode::VelocityPlusGravity, margin);
  clock.lap(&DampedStepProfile::stepContacts);
  const long startTests = gathering_.kept().tests() + gathering_.passNarrowPhases() - testsBefore;
  // DAMPEDINTEGRATION L1: RESOLVECOLLISIONS.
  resolveCollisions(world, dt, margin, touched, totals, stats);
  clock.lap(&DampedStepProfile::collisionPasses);
  // DAMPEDINTEGRATION L2: RESOLVECONTACTS.
  resolveContacts(world, dt, margin, touched, totals, stats);
  clock.lap(&DampedStepProfile::contactPasses);
  // DEVIATION(A.2, §2.5.2): with friction, shock propagation settles the leaning columns the
  // passes leave falling (propagateShockDamped).
  if (friction && params_.shockPropagation) {
    // Every island, those the contact passes settled too: the sweep is not another such pass.
    if (ContactIslands* settled = gathering_.islands()) settled->activateAll();
    const double gdt = world.gravity.norm() * dt;
    stats.events += propagateShockDamped(world, dt, margin, gathering_, stable_,
                                         params_.shockSettledSpeed * gdt,
                                         params_.shockRestingSpeed * gdt, shockLevels_,
                                         params_.shockIterations);
  }
  clock.lap(&DampedStepProfile::shockSweep);
  // DAMPEDINTEGRATION L3: IntegrateObjectVelocities (sleeping bodies stand immovable and are
  // skipped).
  integrateVelocities(world, dt);
  // DAMPEDINTEGRATION L4: DAMPENOBJECTS, whose L22 integrates the positions.
  if (params_.damp) {
    // The support test reads the contacts of the poses the step started from, which L1-L3 have
    // not moved: the last step's final contacts, or on a first step (or in a world moved or
    // changed since) a narrow phase of its own with the same margin.
    static const std::vector<SupportVerdict> asWritten;
    const std::vector<SupportVerdict>* support = &asWritten;
    const double restingMargin = restingContactMargin(world, margin, dt);
    const SupportTestParams supportParams{params_.sleep.supportNormalY,
                                          params_.damping.alignedAngleDeg, restingMargin, margin};
    if (startingContacts) {
      if (!posesUnchanged(world, lastPoses_))
        lastContacts_ = findContacts(world, restingMargin, candidatePairs(world, restingMargin),
                                     &gathering_.kept());
      if (params_.damping.supportTest) support = &supportTest_(world, lastContacts_, supportParams);
    }
    // Coulomb's cone bounds the rests (markFrictionSlides); a frictionless world is A.2's.
    if (friction) {
      slideVerdicts_.assign(support->begin(), support->end());
      markFrictionSlides(world, lastContacts_, slideVerdicts_, &slideLists_, supportParams,
                         params_.damping.linearSmallEps * world.gravity.norm() * dt);
      support = &slideVerdicts_;
    }
    // DEVIATION(DAMPENOBJECTS L2): with supportedOnly, a body in contact is damped only when
    // its contacts reach down to an immovable one (DampingParams::supportedOnly says why).
    if (params_.damping.supportedOnly)
      keepSupported(world, lastContacts_, touched, supportedIslands_);
    dampenObjects(world, dt, touched, params_.damping, params_.impulse.integrator, *support,
                  &dampedPoses_);
  } else {
    // DAMPENOBJECTS L22: without damping, its position update alone.
    integratePositions(world, dt, params_.impulse.integrator, dampedPoses_);
  }
  clock.lap(&DampedStepProfile::velocitiesAndDamping);
  // DAMPEDINTEGRATION L5: FIXCONTACTCONSTRAINTS, and the contacts after it.
  // Kept as the next step's starting contacts, where the support test reads them.
  const long testsBeforeFix = gathering_.kept().tests();
  fixContacts(world, dt, margin);
  const long fixTests = gathering_.kept().tests() - testsBeforeFix;
  const std::vector<ContactManifold>& contacts = lastContacts_;
  if (startingContacts) {
    lastPoses_.resize(n);
    for (std::size_t i = 0; i < n; ++i) lastPoses_[i] = {world.bodies[i].s.x, world.bodies[i].s.q};
  }
  clock.lap(&DampedStepProfile::fixContacts);
  // DAMPEDINTEGRATION L6: SETGEOMETRICALLYSTABLE.
  if (params_.useGeometricStability) {
    stable_ = stability_(world, contacts, params_.geometricStability);
    sleeping_.holdStability(stable_);
  }
  clock.lap(&DampedStepProfile::stability);
  endStep(world, dt, contacts, stats);
  clock.lap(&DampedStepProfile::sleeping);
  if (profile_) {
    ++profile_->workSteps;
    profile_->narrowPhases +=
        gathering_.kept().tests() + gathering_.passNarrowPhases() - testsBefore;
    profile_->passNarrowPhases += gathering_.passNarrowPhases() - passTestsBefore;
    profile_->startNarrowPhases += startTests;
    profile_->fixNarrowPhases += fixTests;
    profile_->axisChecks +=
        gathering_.passAxisChecks() + gathering_.kept().axisChecks() - axisChecksBefore;
    profile_->keptNarrowPhases += gathering_.kept().reuses() - reusesBefore;
    profile_->touchingPairs += stats.contacts;
    profile_->passes += stats.passes;
  }
  return stats;
}

void DampedIntegrationStepper::resolveCollisions(World& world, double dt, double margin,
                                                 std::vector<char>& touched, FrictionTotals* totals,
                                                 StepStats& stats) {
  // The hook runs only when needed, so with both techniques off the step is A.2 as written.
  const bool hooked = params_.sleep.enabled || params_.plausibility.enabled;
  const BeforeCollide hook = [this](World& w, ImpulseContact& c, const CollideCall& call) {
    sleeping_.beforeCollide(w, c, call);
    // §4.2: high-velocity collisions only; contacts (RESOLVECONTACTS) are never perturbed.
    plausibility_.perturb(c, approachSpeed(w, c, call.gravity, call.dt));
  };
  // DEVIATION(RESOLVECOLLISIONS L1): with impactPasses, passes beyond the thesis' while the last
  // one still stopped an impact (impactPasses says why).
  const double impactReach = params_.impactPasses > 0 ? params_.impactReach : 0.0;
  int impacts = 0;
  // RESOLVECOLLISIONS L1, L5: the passes, each colliding with COLLISION_RESTITUTION and
  // VELOCITY_NO_GRAVITY, positions predicted with gravity.
  const int iterations = params_.impulse.collisionIterations;
  for (int i = 0; i < iterations + params_.impactPasses; ++i) {
    if (i >= iterations && impacts == 0) break;
    const PassResult pass =
        impulsePass(world, dt, world.restitution, GravityMode::VelocityPlusGravity,
                    GravityMode::VelocityNoGravity, margin, gathering_, stable_,
                    params_.dampCollidingBodies ? &touched : nullptr,
                    hooked ? hook : BeforeCollide{}, totals,
                    // Islands whose passes changed nothing sit out the rest of the loop.
                    params_.islandSettling ? IslandSettling::Unchanged : IslandSettling::Never,
                    impactReach);
    stats.events += pass.impulses;
    ++stats.passes;
    impacts = pass.impacts;
    // A pass that changed no body leaves the world as it found it: every later collision pass
    // would repeat it, changing nothing. Stopping here gives the same bits, sooner.
    if (!pass.changed && params_.stopUnchangedCollisionPasses) break;
    if (pass.settled) break;
  }
}

void DampedIntegrationStepper::resolveContacts(World& world, double dt, double margin,
                                               std::vector<char>& touched, FrictionTotals* totals,
                                               StepStats& stats) {
  const BeforeCollide hook = [this](World& w, ImpulseContact& c, const CollideCall& call) {
    sleeping_.beforeCollide(w, c, call);
  };
  if (ContactIslands* settled = gathering_.islands()) settled->activateAll();
  // RESOLVECONTACTS L1, L5: the passes, restitution from -1 towards 0, gravity trick.
  const int iterations = params_.impulse.contactIterations;
  for (int i = 1; i <= iterations; ++i) {
    const PassResult pass = impulsePass(
        world, dt, -1.0 + static_cast<double>(i) / iterations, GravityMode::VelocityPlusGravity,
        GravityMode::VelocityPlusGravity, margin, gathering_, stable_, &touched,
        params_.sleep.enabled ? hook : BeforeCollide{}, totals,
        params_.islandSettling ? IslandSettling::Unapproached : IslandSettling::Never);
    stats.events += pass.impulses;
    ++stats.passes;
    if (pass.settled) break;
  }
}

void DampedIntegrationStepper::fixContacts(World& world, double dt, double margin) {
  const double restingMargin = restingContactMargin(world, margin, dt);
  // Sleeping bodies still stand in as immovable, so none moves.
  std::vector<ContactManifold>& contacts = lastContacts_;
  // The broad phase of these contacts, from the step's candidates when they cover it.
  std::vector<std::pair<int, int>>& pairs = fixLists_.pairs;
  const bool havePairs = gathering_.stepPairs(world, restingMargin, pairs);
  // Every narrow phase of the step's end goes through the kept ones: the pairs that stand as
  // they stood when last tested (and the next step's start tests these same poses) are not
  // tested again.
  KeptNarrowPhase& kept = gathering_.kept();
  if (!params_.fixContactConstraints) {
    if (havePairs)
      findContacts(world, restingMargin, pairs, &kept, contacts);
    else
      findContacts(world, restingMargin, candidatePairs(world, restingMargin), &kept, contacts);
    return;
  }
  // Nudging moves x alone: the bodies it moved are those whose x changed.
  const std::size_t n = world.bodies.size();
  std::vector<Vec3>& before = fixLists_.before;
  before.resize(n);
  for (std::size_t i = 0; i < n; ++i) before[i] = world.bodies[i].s.x;
  // SETGEOMETRICALLYSTABLE, for the next step's COLLIDE L11-L14, needs the contacts after
  // DAMPEDINTEGRATION L5: those it found, with the pairs of the bodies it nudged found again.
  if (fixContactConstraints(world, restingMargin, params_.fixContacts, dt, &contacts,
                            havePairs ? &pairs : nullptr, &kept, &fixLists_.order) > 0) {
    std::vector<char>& nudged = fixLists_.nudged;
    nudged.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      nudged[i] = static_cast<char>(world.bodies[i].s.x != before[i]);
    // The broad phase at the nudged poses from the step's candidates too, when they cover it.
    const bool haveNudgedPairs = gathering_.stepPairs(world, restingMargin, pairs);
    refindContacts(world, restingMargin, contacts, nudged, &kept, fixLists_.broadPhase,
                   fixLists_.refound, haveNudgedPairs ? &pairs : nullptr);
    contacts.swap(fixLists_.refound);
  }
}

void DampedIntegrationStepper::endStep(World& world, double dt,
                                       const std::vector<ContactManifold>& contacts,
                                       StepStats& stats) {
  const bool sleeping = params_.sleep.enabled;
  // The closest faces of the pairs the narrow phase skipped are recorded as if it had seen
  // them, so a pair that wakes keeps the normal it had (\thesis{§3.3.2}) and waking changes
  // nothing the normal model remembers.
  if (sleeping && gathering_.normals().model() == ContactNormalModel::PreviousClosestFace)
    for (const ContactManifold& m : sleeping_.skippedContacts(world))
      gathering_.normals().remember(world, m);
  gathering_.endStep();
  if (sleeping) {
    sleeping_.end(world, contacts, stable_, dt);
    // The contacts the narrow phase skipped still touch: count them as before sleeping.
    stats.contacts = sleeping_.restingContacts();
  } else {
    stats.contacts = static_cast<int>(contacts.size());
  }
  stats.sleeping = sleeping_.asleepCount();
}

}  // namespace boxsim
