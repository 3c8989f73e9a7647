/// \file
/// DAMPEDINTEGRATION (\alg{A.2}, \thesis{§5.2}), with sleeping bodies (\thesis{§4.5}) and
/// perturbed high-speed collisions (\thesis{§4.2}).
#include "boxsim/impulse_damped/damped_integration.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/impulse_damped/fix_contact_constraints.hpp"

namespace boxsim {

namespace {
bool momentaZero(const BodyState& s) { return s.P == Vec3::Zero() && s.L == Vec3::Zero(); }

/// Restores the stand-ins when a step leaves, normally or by an exception, so the world never
/// keeps a sleeping body's borrowed infinite mass between steps.
template <class Restore>
class ScopeExit {
 public:
  explicit ScopeExit(Restore restore) : restore_(restore) {}
  ScopeExit(const ScopeExit&) = delete;
  ScopeExit& operator=(const ScopeExit&) = delete;
  ~ScopeExit() { restore_(); }

 private:
  Restore restore_;
};
}  // namespace

DampedIntegrationStepper::DampedIntegrationStepper(const DampedIntegrationParams& params)
    : params_(params), normals_(params.impulse.normalModel), plausibility_(params.plausibility) {
  if (params.impulse.collisionIterations < 1 || params.impulse.contactIterations < 1)
    throw std::invalid_argument("damped: collision and contact iterations must be >= 1");
  const SleepParams& s = params.sleep;
  if (!std::isfinite(s.timeToSleep) || s.timeToSleep <= 0.0)
    throw std::invalid_argument("damped: the time to sleep must be a finite number > 0 s");
  if (!std::isfinite(s.wakeSpeed) || s.wakeSpeed < 0.0 || !std::isfinite(s.wakeImpulse) ||
      s.wakeImpulse < 0.0)
    throw std::invalid_argument("damped: the wake thresholds must be finite numbers >= 0 g dt");
  if (!(s.supportNormalY > 0.0 && s.supportNormalY < 1.0))
    throw std::invalid_argument("damped: supportNormalY must lie in (0, 1)");
}

std::map<std::string, std::string> DampedIntegrationStepper::parameters() const {
  const DampingParams& d = params_.damping;
  const SleepParams& s = params_.sleep;
  const PlausibilityParams& p = params_.plausibility;
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
          {"slop_per_l", shortestText(params_.fixContacts.slop)},
          {"sleep", s.enabled ? "on" : "off"},
          {"sleep_time_s", shortestText(s.timeToSleep)},
          {"wake_speed_g_dt", shortestText(s.wakeSpeed)},
          {"wake_impulse_g_dt", shortestText(s.wakeImpulse)},
          {"support_normal_y", shortestText(s.supportNormalY)},
          {"plausibility", p.enabled ? "on" : "off"},
          {"plausibility_speed_m_per_s", shortestText(p.speedThreshold)},
          {"plausibility_max_deg", shortestText(p.maxAngleDeg)},
          {"seed", std::to_string(p.seed)}};
}

// --- sleeping (§4.5) ---------------------------------------------------------------------

void DampedIntegrationStepper::standIn(World& world, int body) {
  RigidBody& b = world.bodies[body];
  saved_[body] = MassProperties{b.mass, b.invMass, b.IbodyInvDiag};
  b.mass = std::numeric_limits<double>::infinity();
  b.invMass = 0.0;
  b.IbodyInvDiag = Vec3::Zero();
  b.immovable = true;
  b.updateDerived();
  standing_[body] = 1;
}

void DampedIntegrationStepper::restore(World& world, int body) {
  if (!standing_[body]) return;
  RigidBody& b = world.bodies[body];
  b.mass = saved_[body].mass;
  b.invMass = saved_[body].invMass;
  b.IbodyInvDiag = saved_[body].IbodyInvDiag;
  b.immovable = false;
  b.updateDerived();
  standing_[body] = 0;
}

void DampedIntegrationStepper::restoreAll(World& world) {
  for (std::size_t i = 0; i < standing_.size() && i < world.bodies.size(); ++i)
    restore(world, static_cast<int>(i));
}

void DampedIntegrationStepper::prepareSleep(World& world) {
  const std::size_t n = world.bodies.size();
  if (asleep_.size() > n) {
    // Bodies were removed: indices no longer name the same bodies, so everything wakes.
    asleep_.clear();
    stillSteps_.clear();
    resting_.clear();
  }
  // Bodies added since the last step start awake, with no remembered contacts.
  asleep_.resize(n, 0);
  standing_.assign(n, 0);
  stillSteps_.resize(n, 0);
  sleepState_.resize(n);
  sleepStable_.resize(n, 0);
  saved_.resize(n);
  restingOf_.assign(n, {});
  for (std::size_t e = 0; e < resting_.size(); ++e) {
    restingOf_[resting_[e].a].push_back(static_cast<int>(e));
    restingOf_[resting_[e].b].push_back(static_cast<int>(e));
  }
  if (!params_.sleep.enabled) {
    asleep_.assign(n, 0);
    return;
  }
  std::vector<int> disturbed;
  for (std::size_t i = 0; i < n; ++i) {
    if (!asleep_[i]) continue;
    // Made immovable from outside (a body waiting for its launch): no longer ours to hold.
    if (world.bodies[i].immovable) {
      asleep_[i] = 0;
      continue;
    }
    // A kick or a move from outside the stepper wakes the body.
    if (!(world.bodies[i].s == sleepState_[i])) disturbed.push_back(static_cast<int>(i));
    standIn(world, static_cast<int>(i));
  }
  for (int i : disturbed) wake(world, i);
  // A sleeping body whose support became movable from outside (a body that waited immovable
  // for its launch) wakes: its support is no longer guaranteed to stay put.
  for (const ContactManifold& c : resting_)
    for (const int upper : {c.a, c.b}) {
      const int lower = upper == c.a ? c.b : c.a;
      if (asleep_[upper] && supportedBy(c, upper) && !world.bodies[lower].immovable)
        wake(world, upper);
    }
}

bool DampedIntegrationStepper::supportedBy(const ContactManifold& contact, int upper) const {
  // The normal runs from a to b; seen from `upper` it must point up, from the other body to it.
  const double up = upper == contact.b ? contact.normal.y() : -contact.normal.y();
  return up > params_.sleep.supportNormalY;
}

void DampedIntegrationStepper::wake(World& world, int body) {
  std::vector<int> pending{body};
  while (!pending.empty()) {
    const int i = pending.back();
    pending.pop_back();
    if (!asleep_[i]) continue;
    asleep_[i] = 0;
    stillSteps_[i] = 0;
    restore(world, i);
    // Spreading: the sleeping bodies this one supports may lose their support.
    for (int e : restingOf_[i]) {
      const ContactManifold& c = resting_[e];
      const int other = c.a == i ? c.b : c.a;
      if (asleep_[other] && supportedBy(c, other)) pending.push_back(other);
    }
  }
}

double DampedIntegrationStepper::pointInverseMass(const World& world, int body, const Vec3& point,
                                                  const Vec3& n) const {
  // The body's own mass properties, not the stand-in's: 1/m + n·((I⁻¹ (r × n)) × r), the
  // velocity change of the material point at `point` along n per unit impulse along n.
  const RigidBody& b = world.bodies[body];
  const MassProperties m =
      standing_[body] ? saved_[body] : MassProperties{b.mass, b.invMass, b.IbodyInvDiag};
  const Mat3 Iinv = b.R * m.IbodyInvDiag.asDiagonal() * b.R.transpose();
  const Vec3 r = point - b.s.x;
  return m.invMass + n.dot((Iinv * r.cross(n)).cross(r));
}

void DampedIntegrationStepper::beforeCollide(World& world, ImpulseContact& contact,
                                             const CollideCall& call, bool collisionPass) {
  if (params_.sleep.enabled && asleep_[contact.a] != asleep_[contact.b]) {
    // The broad phase drops pairs of two immovable bodies, so the other body is awake and
    // movable: this is the only place a sleeping body can be disturbed from inside a step.
    const int sleeper = asleep_[contact.a] ? contact.a : contact.b;
    const double u = world.gravity.norm() * call.dt;
    bool wakes = approachSpeed(world, contact, call.gravity, call.dt) > params_.sleep.wakeSpeed * u;
    if (!wakes) {
      const double j = collideImpulse(world, contact, call.restitution, call.gravity, call.dt);
      wakes = j * pointInverseMass(world, sleeper, contact.point, contact.normal) >
              params_.sleep.wakeImpulse * u;
    }
    // Woken before its COLLIDE, the body takes its share of this very impulse.
    if (wakes) wake(world, sleeper);
  }
  // §4.2: high-velocity collisions only; contacts (RESOLVECONTACTS) are never perturbed.
  if (collisionPass)
    plausibility_.perturb(contact, approachSpeed(world, contact, call.gravity, call.dt));
}

void DampedIntegrationStepper::endSleep(World& world, const std::vector<ContactManifold>& contacts,
                                        const std::vector<BodyState>& start, double dt) {
  const std::size_t n = world.bodies.size();
  // The contact graph at the end of the step: what the narrow phase found, plus the remembered
  // manifolds of pairs it skipped because both bodies stood immovable (neither has moved).
  std::vector<ContactManifold> next = contacts;
  next.reserve(contacts.size() + resting_.size());
  for (const ContactManifold& c : resting_)
    if (world.bodies[c.a].immovable && world.bodies[c.b].immovable) next.push_back(c);
  std::sort(next.begin(), next.end(), [](const ContactManifold& l, const ContactManifold& r) {
    return l.a < r.a || (l.a == r.a && l.b < r.b);
  });
  resting_.swap(next);
  restingOf_.assign(n, {});
  for (std::size_t e = 0; e < resting_.size(); ++e) {
    restingOf_[resting_[e].a].push_back(static_cast<int>(e));
    restingOf_[resting_[e].b].push_back(static_cast<int>(e));
  }
  // A sleeping body that an awake one penetrates beyond the slop (FIXCONTACTCONSTRAINTS could
  // not push the awake one out, e.g. it lies below) wakes, so the next step can separate them.
  for (const ContactManifold& m : contacts) {
    if (asleep_[m.a] == asleep_[m.b]) continue;
    const double ell = std::min(world.bodies[m.a].halfExtents.minCoeff(),
                                world.bodies[m.b].halfExtents.minCoeff());
    if (m.depth > params_.fixContacts.slop * ell) wake(world, asleep_[m.a] ? m.a : m.b);
  }
  restoreAll(world);
  // Stillness: momenta exactly zero and a pose the step did not change, bit for bit.
  for (std::size_t i = 0; i < n; ++i) {
    const RigidBody& b = world.bodies[i];
    if (b.immovable || asleep_[i]) continue;
    const bool still =
        momentaZero(b.s) && b.s.x == start[i].x && b.s.q.coeffs() == start[i].q.coeffs();
    stillSteps_[i] = still ? stillSteps_[i] + 1 : 0;
  }
  // Falling asleep from the ground up: a still body sleeps once every support sleeps or is
  // immovable. Each sweep settles at least one more level of a pile, so this ends.
  const long steps = std::max(1L, std::lround(params_.sleep.timeToSleep / dt));
  for (bool changed = true; changed;) {
    changed = false;
    for (std::size_t i = 0; i < n; ++i) {
      if (asleep_[i] || world.bodies[i].immovable || stillSteps_[i] < steps) continue;
      bool supported = true;
      for (int e : restingOf_[i]) {
        const ContactManifold& c = resting_[e];
        const int other = c.a == static_cast<int>(i) ? c.b : c.a;
        const bool holds = asleep_[other] || world.bodies[other].immovable;
        if (supportedBy(c, static_cast<int>(i)) && !holds) supported = false;
      }
      if (!supported) continue;
      asleep_[i] = 1;
      sleepState_[i] = world.bodies[i].s;
      sleepStable_[i] = stable_[i];
      changed = true;
    }
  }
}

// --- the step -----------------------------------------------------------------------------

StepStats DampedIntegrationStepper::step(World& world, double dt) {
  StepStats stats;
  const std::size_t n = world.bodies.size();
  if (stable_.size() != n || !params_.useGeometricStability) stable_.assign(n, 0);
  // ℓ before sleeping bodies stand in as immovable, which would hide them from it.
  const double margin = params_.impulse.contactMargin * smallestHalfExtent(world);
  const bool sleeping = params_.sleep.enabled;
  // The guard comes first: prepareSleep already turns sleeping bodies into immovable stand-ins,
  // and their real mass properties must come back whatever happens after.
  const ScopeExit restoreOnExit([&] { restoreAll(world); });
  prepareSleep(world);
  const auto countAsleep = [&] {
    return static_cast<int>(std::count(asleep_.begin(), asleep_.end(), 1));
  };
  // §4.5: with every movable body asleep nothing can happen; the step costs nothing.
  if (sleeping) {
    bool anyAwake = false;
    for (std::size_t i = 0; i < n && !anyAwake; ++i) anyAwake = !world.bodies[i].immovable;
    if (!anyAwake) {
      stats.sleeping = countAsleep();
      stats.contacts = static_cast<int>(resting_.size());
      return stats;
    }
  }
  std::vector<BodyState> start;
  if (sleeping) {
    start.reserve(n);
    for (const RigidBody& b : world.bodies) start.push_back(b.s);
  }
  // The hooks run only when needed, so with both techniques off the step is A.2 as written.
  const bool hooked = sleeping || params_.plausibility.enabled;
  const BeforeCollide collisionHook = [this](World& w, ImpulseContact& c, const CollideCall& call) {
    beforeCollide(w, c, call, true);
  };
  const BeforeCollide contactHook = [this](World& w, ImpulseContact& c, const CollideCall& call) {
    beforeCollide(w, c, call, false);
  };
  // L1: RESOLVECOLLISIONS — positions predicted with gravity, impulses without; high-speed
  // collisions perturbed (§4.2).
  for (int i = 0; i < params_.impulse.collisionIterations; ++i)
    stats.events += impulsePass(world, dt, world.restitution, GravityMode::VelocityPlusGravity,
                                GravityMode::VelocityNoGravity, margin, normals_, stable_, nullptr,
                                hooked ? collisionHook : BeforeCollide{})
                        .impulses;
  // L2: RESOLVECONTACTS — restitution from -1 towards 0 (RESOLVECONTACTS L5), gravity trick.
  std::vector<char> touched(n, 0);
  const int iterations = params_.impulse.contactIterations;
  for (int i = 1; i <= iterations; ++i)
    stats.events += impulsePass(world, dt, -1.0 + static_cast<double>(i) / iterations,
                                GravityMode::VelocityPlusGravity, GravityMode::VelocityPlusGravity,
                                margin, normals_, stable_, &touched,
                                sleeping ? contactHook : BeforeCollide{})
                        .impulses;
  // L3: IntegrateObjectVelocities (sleeping bodies stand immovable and are skipped).
  for (RigidBody& body : world.bodies)
    if (!body.immovable) {
      body.s.P += dt * body.mass * world.gravity;
      body.updateVelocities();
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
  // L5: FIXCONTACTCONSTRAINTS; sleeping bodies are held.
  if (params_.fixContactConstraints)
    fixContactConstraints(world, restingMargin, params_.fixContacts, asleep_);
  // L6: SETGEOMETRICALLYSTABLE, for the next step's COLLIDE L11-L14.
  const std::vector<ContactManifold> contacts = findContacts(world, restingMargin);
  if (params_.useGeometricStability) {
    stable_ = setGeometricallyStable(world, contacts, params_.geometricStability);
    // A sleeping body stood in as immovable, which always counts as stable; it keeps the flag
    // it had awake, so waking it gives back the behaviour it would have had.
    for (std::size_t i = 0; i < n; ++i)
      if (asleep_[i]) stable_[i] = sleepStable_[i];
  }
  // The closest faces of the pairs the narrow phase skipped are recorded as if it had seen
  // them, so a pair that wakes keeps the normal it had (\thesis{§3.3.2}) and waking changes
  // nothing the normal model remembers.
  if (sleeping && normals_.model() == ContactNormalModel::PreviousClosestFace) {
    std::vector<ContactManifold> skipped;
    for (const ContactManifold& c : resting_)
      if (world.bodies[c.a].immovable && world.bodies[c.b].immovable) skipped.push_back(c);
    normals_.contactsOf(world, skipped);
  }
  normals_.endStep();
  if (sleeping) {
    endSleep(world, contacts, start, dt);
    // The contacts the narrow phase skipped still touch: count them as before sleeping.
    stats.contacts = static_cast<int>(resting_.size());
  } else {
    stats.contacts = static_cast<int>(contacts.size());
  }
  stats.sleeping = countAsleep();
  return stats;
}

}  // namespace boxsim
