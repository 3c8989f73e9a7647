/// \file
/// Sleeping bodies at rest (computational stability, \thesis{§4.5}): stand-ins, wake tests,
/// spreading, and falling asleep from the ground up.
#include "boxsim/impulse_damped/sleeping.hpp"

#include "boxsim/core/newtonian_impulse.hpp"

#include <algorithm>
#include <iterator>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace boxsim {

namespace {
bool momentaZero(const BodyState& s) { return s.P == Vec3::Zero() && s.L == Vec3::Zero(); }
}  // namespace

Sleeping::Sleeping(const SleepParams& params, double slop)
    : params_(params), slop_(slop), chatter_(params.chatterEnvelope, slop) {
  const SleepParams& s = params;
  if (!std::isfinite(s.timeToSleep) || s.timeToSleep <= 0.0)
    throw std::invalid_argument("damped: the time to sleep must be a finite number > 0 s");
  if (!std::isfinite(s.wakeSpeed) || s.wakeSpeed < 0.0 || !std::isfinite(s.wakeImpulse) ||
      s.wakeImpulse < 0.0)
    throw std::invalid_argument("damped: the wake thresholds must be finite numbers >= 0 g dt");
  if (!(s.supportNormalY > 0.0 && s.supportNormalY < 1.0))
    throw std::invalid_argument("damped: supportNormalY must lie in (0, 1)");
  if (!std::isfinite(s.chatterEnvelope) || s.chatterEnvelope <= 0.0)
    throw std::invalid_argument("damped: the chatter envelope must be a finite number > 0 (units of l)");
}

void Sleeping::standIn(World& world, int body) {
  RigidBody& b = world.bodies[body];
  saved_[body] = MassProperties{b.mass, b.invMass, b.IbodyInvDiag};
  b.mass = std::numeric_limits<double>::infinity();
  b.invMass = 0.0;
  b.IbodyInvDiag = Vec3::Zero();
  b.immovable = true;
  b.updateDerived();
  standing_[body] = 1;
}

void Sleeping::restore(World& world, int body) {
  if (!standing_[body]) return;
  RigidBody& b = world.bodies[body];
  b.mass = saved_[body].mass;
  b.invMass = saved_[body].invMass;
  b.IbodyInvDiag = saved_[body].IbodyInvDiag;
  b.immovable = false;
  b.updateDerived();
  standing_[body] = 0;
}

void Sleeping::restoreAll(World& world) {
  for (std::size_t i = 0; i < standing_.size() && i < world.bodies.size(); ++i)
    restore(world, static_cast<int>(i));
}

int Sleeping::asleepCount() const {
  return static_cast<int>(std::count(asleep_.begin(), asleep_.end(), 1));
}

bool Sleeping::begin(World& world) {
  const std::size_t n = world.bodies.size();
  if (asleep_.size() > n) {
    // Bodies were removed: indices no longer name the same bodies, so everything wakes.
    asleep_.clear();
    stillSteps_.clear();
    resting_.clear();
    chatter_.resize(0);
  }
  // Bodies added since the last step start awake, with no remembered contacts.
  asleep_.resize(n, 0);
  standing_.assign(n, 0);
  stillSteps_.resize(n, 0);
  chatter_.resize(n);
  sleepState_.resize(n);
  sleepStable_.resize(n, 0);
  saved_.resize(n);
  indexResting(n);
  if (!params_.enabled) {
    asleep_.assign(n, 0);
    return true;
  }
  std::vector<int>& disturbed = disturbed_;
  disturbed.clear();
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
  // §4.5: with every movable body asleep nothing can happen; the step costs nothing.
  bool anyAwake = false;
  for (std::size_t i = 0; i < n && !anyAwake; ++i) anyAwake = !world.bodies[i].immovable;
  if (!anyAwake) return false;
  start_.clear();
  start_.reserve(n);
  for (const RigidBody& b : world.bodies) start_.push_back(b.s);
  return true;
}

bool Sleeping::supportedBy(const ContactManifold& contact, int upper) const {
  // The normal runs from a to b; seen from `upper` it must point up, from the other body to it.
  const double up = upper == contact.b ? contact.normal.y() : -contact.normal.y();
  return up > params_.supportNormalY;
}

bool Sleeping::restsFor(int i, long steps) const {
  if (stillSteps_[i] >= steps) return true;
  if (!params_.chatterDetection || !chatter_.chatters(static_cast<std::size_t>(i))) return false;
  // Chatter needs something to chatter on: a free body drifting slowly is not at rest.
  for (int e : restingOf(static_cast<std::size_t>(i)))
    if (supportedBy(resting_[e], i)) return true;
  return false;
}

void Sleeping::wake(World& world, int body) {
  std::vector<int>& pending = pending_;
  pending.assign(1, body);
  while (!pending.empty()) {
    const int i = pending.back();
    pending.pop_back();
    if (!asleep_[i]) continue;
    asleep_[i] = 0;
    stillSteps_[i] = 0;
    chatter_.reset(static_cast<std::size_t>(i));
    restore(world, i);
    // Spreading: the sleeping bodies this one supports may lose their support.
    for (int e : restingOf(static_cast<std::size_t>(i))) {
      const ContactManifold& c = resting_[e];
      const int other = c.a == i ? c.b : c.a;
      if (asleep_[other] && supportedBy(c, other)) pending.push_back(other);
    }
  }
}

void Sleeping::indexResting(std::size_t n) {
  // A counting sort by body, into one flat list that keeps its room from step to step; each
  // body's contacts in resting_'s order, as pushing them one by one would list them.
  restingStart_.assign(n + 1, 0);
  for (const ContactManifold& c : resting_) {
    ++restingStart_[static_cast<std::size_t>(c.a) + 1];
    ++restingStart_[static_cast<std::size_t>(c.b) + 1];
  }
  for (std::size_t i = 0; i < n; ++i) restingStart_[i + 1] += restingStart_[i];
  restingIndex_.resize(restingStart_[n]);
  for (std::size_t e = 0; e < resting_.size(); ++e) {
    // Fill from each body's start, then shift the starts back (the last body's end stays).
    restingIndex_[restingStart_[static_cast<std::size_t>(resting_[e].a)]++] = static_cast<int>(e);
    restingIndex_[restingStart_[static_cast<std::size_t>(resting_[e].b)]++] = static_cast<int>(e);
  }
  for (std::size_t i = n; i > 0; --i) restingStart_[i] = restingStart_[i - 1];
  restingStart_[0] = 0;
}

double Sleeping::pointInverseMass(const World& world, int body, const Vec3& r,
                                  const Vec3& n) const {
  // The body's own mass properties, not the stand-in's: 1/m + n·((I⁻¹ (r × n)) × r), the
  // velocity change of the material point at `point` along n per unit impulse along n.
  const RigidBody& b = world.bodies[body];
  const MassProperties m =
      standing_[body] ? saved_[body] : MassProperties{b.mass, b.invMass, b.IbodyInvDiag};
  const Mat3 Iinv = b.R * m.IbodyInvDiag.asDiagonal() * b.R.transpose();
  return m.invMass + rotationalInverseMass(Iinv, r, n);
}

void Sleeping::beforeCollide(World& world, const ImpulseContact& contact,
                             const CollideCall& call) {
  if (!params_.enabled || asleep_[contact.a] == asleep_[contact.b]) return;
  // The broad phase drops pairs of two immovable bodies, so the other body is awake and
  // movable: this is the only place a sleeping body can be disturbed from inside a step.
  const int sleeper = asleep_[contact.a] ? contact.a : contact.b;
  const double u = world.gravity.norm() * call.dt;
  bool wakes = approachSpeed(world, contact, call.gravity, call.dt) > params_.wakeSpeed * u;
  if (!wakes) {
    const double j = collideImpulse(world, contact, call.restitution, call.gravity, call.dt);
    const Vec3& r = sleeper == contact.a ? contact.ra : contact.rb;
    wakes = j * pointInverseMass(world, sleeper, r, contact.normal) >
            params_.wakeImpulse * u;
  }
  // Woken before its COLLIDE, the body takes its share of this very impulse.
  if (wakes) wake(world, sleeper);
}

void Sleeping::holdStability(std::vector<char>& stable) const {
  // A sleeping body stood in as immovable, which always counts as stable; it keeps the flag
  // it had awake, so waking it gives back the behaviour it would have had.
  for (std::size_t i = 0; i < stable.size() && i < asleep_.size(); ++i)
    if (asleep_[i]) stable[i] = sleepStable_[i];
}

const std::vector<ContactManifold>& Sleeping::skippedContacts(const World& world) const {
  std::vector<ContactManifold>& skipped = skipped_;
  skipped.clear();
  for (const ContactManifold& c : resting_)
    if (world.bodies[c.a].immovable && world.bodies[c.b].immovable) skipped.push_back(c);
  return skipped;
}

void Sleeping::end(World& world, const std::vector<ContactManifold>& contacts,
                   const std::vector<char>& stable, double dt) {
  const std::size_t n = world.bodies.size();
  // The contact graph at the end of the step: what the narrow phase found, plus the remembered
  // manifolds of pairs it skipped because both bodies stood immovable (neither has moved).
  std::vector<ContactManifold>& next = next_;
  std::vector<ContactManifold>& remembered = remembered_;
  remembered.clear();
  for (const ContactManifold& c : resting_)
    if (world.bodies[c.a].immovable && world.bodies[c.b].immovable) remembered.push_back(c);
  // By pair. The step's contacts and the remembered ones come in that order each (and a pair
  // is in one list only), so merging them is sorting them; sorted otherwise.
  const auto byPair = [](const ContactManifold& l, const ContactManifold& r) {
    return l.a < r.a || (l.a == r.a && l.b < r.b);
  };
  next.clear();
  if (std::is_sorted(contacts.begin(), contacts.end(), byPair) &&
      std::is_sorted(remembered.begin(), remembered.end(), byPair)) {
    std::merge(contacts.begin(), contacts.end(), remembered.begin(), remembered.end(),
               std::back_inserter(next), byPair);
  } else {
    next.assign(contacts.begin(), contacts.end());
    next.insert(next.end(), remembered.begin(), remembered.end());
    std::sort(next.begin(), next.end(), byPair);
  }
  resting_.swap(next);
  indexResting(n);
  // A sleeping body that an awake one penetrates beyond the slop (FIXCONTACTCONSTRAINTS could
  // not push the awake one out, e.g. it lies below) wakes, so the next step can separate them.
  for (const ContactManifold& m : contacts) {
    if (asleep_[m.a] == asleep_[m.b]) continue;
    const double ell = std::min(world.bodies[m.a].halfExtents.minCoeff(),
                                world.bodies[m.b].halfExtents.minCoeff());
    if (m.depth > slop_ * ell) wake(world, asleep_[m.a] ? m.a : m.b);
  }
  restoreAll(world);
  // Stillness: a pose the step did not change, bit for bit (and with stillByPose off, momenta
  // exactly zero); and, with chatter detection, the window of each awake body.
  const long steps = std::max(1L, std::lround(params_.timeToSleep / dt));
  for (std::size_t i = 0; i < n; ++i) {
    const RigidBody& b = world.bodies[i];
    if (b.immovable || asleep_[i]) continue;
    const bool still = (params_.stillByPose || momentaZero(b.s)) && b.s.x == start_[i].x &&
                       b.s.q.coeffs() == start_[i].q.coeffs();
    stillSteps_[i] = still ? stillSteps_[i] + 1 : 0;
    if (params_.chatterDetection) chatter_.record(i, b, world.gravity, steps);
  }
  // Falling asleep from the ground up: a body at rest sleeps once every support sleeps or is
  // immovable. Each sweep settles at least one more level of a pile, so this ends.
  for (bool changed = true; changed;) {
    changed = false;
    for (std::size_t i = 0; i < n; ++i) {
      if (asleep_[i] || world.bodies[i].immovable || !restsFor(static_cast<int>(i), steps))
        continue;
      bool supported = true;
      for (int e : restingOf(static_cast<std::size_t>(i))) {
        const ContactManifold& c = resting_[e];
        const int other = c.a == static_cast<int>(i) ? c.b : c.a;
        const bool holds = asleep_[other] || world.bodies[other].immovable;
        if (supportedBy(c, static_cast<int>(i)) && !holds) supported = false;
      }
      if (!supported) continue;
      // A chattering body, or one whose pose the snap holds, is put to rest: the momenta it
      // keeps go nowhere (ChatterHistory, SleepParams::stillByPose).
      RigidBody& b = world.bodies[i];
      if (!momentaZero(b.s)) {
        b.s.P.setZero();
        b.s.L.setZero();
        b.updateDerived();
      }
      chatter_.reset(i);
      asleep_[i] = 1;
      sleepState_[i] = b.s;
      sleepStable_[i] = stable[i];
      changed = true;
    }
  }
}

}  // namespace boxsim
