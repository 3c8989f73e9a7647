/// \file
/// COLLIDE and the predict–gather–collide–revert pass of \alg{A.2}.
#include "boxsim/impulse_damped/impulse_pass.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/core/newtonian_impulse.hpp"

namespace boxsim {

namespace {
void addVelocity(RigidBody& body, const Vec3& deltaV) {
  if (body.immovable) return;
  body.s.P += body.mass * deltaV;
  body.v = body.invMass * body.s.P;  // L is unchanged, so ω = I⁻¹ L is too
}

/// What COLLIDE may change of a body, to tell whether it did, bit for bit.
struct BodyMomenta {
  Vec3 P, L;
  bool immovable;
  explicit BodyMomenta(const RigidBody& body) : P(body.s.P), L(body.s.L), immovable(body.immovable) {}
  bool same(const RigidBody& body) const {
    return sameBits(P, body.s.P) && sameBits(L, body.s.L) && immovable == body.immovable;
  }
};

/// COLLIDE L5-L6, L8: both bodies get deltaV, then the Newtonian impulse at the contact (its
/// point found by COLLIDE L7, ContactNormalTracker::contactOf); returns j.
double impulseWithGravity(RigidBody& a, RigidBody& b, const ImpulseContact& contact,
                          double restitution, const Vec3& deltaV, FrictionTotals* totals,
                          bool restarted) {
  addVelocity(a, deltaV);
  addVelocity(b, deltaV);
  return contactImpulse(a, b, contact, restitution, totals, restarted);
}
}  // namespace

void FrictionTotals::shareWeights(const World& world, const std::vector<ImpulseContact>& contacts,
                                  const std::vector<char>& stable, double dt) {
  for (int i : shared_) {
    share_[static_cast<std::size_t>(i)] = 0.0;
    rises_[static_cast<std::size_t>(i)] = 0.0;
  }
  shared_.clear();
  edges_.clear();
  if (stable.empty()) return;
  const std::size_t n = world.bodies.size();
  share_.resize(n, 0.0);
  rises_.resize(n, 0.0);
  const double g = world.gravity.norm();
  if (!(g > 0.0)) return;
  up_ = -world.gravity / g;
  restingSpeed_ = g * dt;
  // Each frictional contact whose normal pushes a movable body against gravity carries a part of
  // its load in proportion to how far the normal rises (n · up: a side contact carries none).
  for (const ImpulseContact& c : contacts) {
    if (c.friction.frictionless()) continue;
    const double rise = c.normal.dot(up_);  // the normal runs from a to b
    const int carried = rise > 0.0 ? c.b : rise < 0.0 ? c.a : -1;
    if (carried < 0 || world.bodies[carried].immovable) continue;
    edges_.push_back({carried, carried == c.b ? c.a : c.b, std::abs(rise)});
    const std::size_t k = static_cast<std::size_t>(carried);
    if (rises_[k] == 0.0) shared_.push_back(carried);
    rises_[k] += std::abs(rise);
  }
  if (shared_.empty()) return;
  // From the top down, each body's load (its weight and what the bodies it carries put on it)
  // is spread over its supports and passed on to the movable ones under it.
  const auto height = [&](int i) { return up_.dot(world.bodies[i].s.x); };
  std::sort(shared_.begin(), shared_.end(),
            [&](int i, int j) { return height(i) > height(j) || (height(i) == height(j) && i < j); });
  std::sort(edges_.begin(), edges_.end(), [](const Edge& x, const Edge& y) {
    return x.carried < y.carried || (x.carried == y.carried && x.under < y.under);
  });
  for (int i : shared_) share_[static_cast<std::size_t>(i)] = world.bodies[i].mass * g * dt;
  for (int i : shared_) {
    const std::size_t k = static_cast<std::size_t>(i);
    share_[k] /= rises_[k];  // load per unit rise
    const auto first = std::lower_bound(edges_.begin(), edges_.end(), i,
                                        [](const Edge& e, int carried) { return e.carried < carried; });
    for (auto e = first; e != edges_.end() && e->carried == i; ++e) {
      const std::size_t under = static_cast<std::size_t>(e->under);
      // A lower body that is itself carried takes this contact's part of the load on.
      if (rises_[under] > 0.0 && height(e->under) < height(i)) share_[under] += share_[k] * e->rise;
    }
  }
}

double FrictionTotals::supportShare(const ImpulseContact& contact) const {
  if (shared_.empty()) return 0.0;
  const double rise = contact.normal.dot(up_);
  const int i = rise > 0.0 ? contact.b : rise < 0.0 ? contact.a : -1;
  if (i < 0 || static_cast<std::size_t>(i) >= share_.size()) return 0.0;
  // This contact's part of the load, rise / Σ rise, pressed along its normal (times rise again):
  // m g cos θ Δt for a box alone on a plank tilted by θ.
  return share_[static_cast<std::size_t>(i)] * rise * rise;
}

double contactImpulse(RigidBody& a, RigidBody& b, const ImpulseContact& contact, double restitution,
                      FrictionTotals* totals, bool restarted) {
  if (contact.friction.frictionless())
    return applyNewtonianImpulse(a, b, contact.ra, contact.rb, contact.normal, restitution);
  FrictionSum alone;
  FrictionSum& sum = totals ? totals->at(contact.a, contact.b) : alone;
  // Friction first, on the budget of the passes before, so that the normal impulse, which
  // keeps the bodies apart, has the last word (Catto 2005 orders them so too).
  // A restarted contact's tipping is taken away by COLLIDE L11-L14 itself: no couple for it.
  ContactPatch patch = contact.patch;
  if (restarted) patch.count = 0;
  // A resting contact's budget is at least its part of the load of the body it carries
  // (FrictionTotals::shareWeights), from the first pass on; the impulses' own sum stays apart.
  // Resting: restarted (a geometrically stable body), or approaching in this pass at no more
  // than the g Δt of the gravity trick, and not separating. Between two movable bodies the
  // gravity trick adds g Δt to both, so the impulses give such a contact no budget at all (two
  // cubes stacked on a 30° plank slid 2.0 and 3.4 m in 2 s, Coulomb: 1.3 m both). Applied to
  // every contact, separating ones too, the floor kept heaps restless (the 343-cube pile with
  // μ = 0.5 had 52 J at 14 s instead of 4 J, the clump on the ground never slept whole).
  const double impulses = sum.normal;
  bool floorIt = restarted;
  if (totals && !restarted) {
    const double approach = -relativeNormalVelocity(a, b, contact.ra, contact.rb, contact.normal);
    floorIt = approach >= 0.0 && approach <= totals->restingSpeed();
  }
  if (totals && floorIt) sum.normal = std::max(impulses, totals->supportShare(contact));
  applyPatchFriction(a, b, contact.ra, contact.rb, contact.normal, contact.friction, patch, sum);
  sum.normal = impulses;
  const double j = applyNewtonianImpulse(a, b, contact.ra, contact.rb, contact.normal, restitution);
  sum.normal = restarted ? std::max(sum.normal, j) : sum.normal + j;
  return j;
}

double collide(World& world, const ImpulseContact& contact, double restitution, GravityMode gravity,
               double dt, const std::vector<char>& stable, FrictionTotals* totals) {
  RigidBody& a = world.bodies[contact.a];
  RigidBody& b = world.bodies[contact.b];
  // COLLIDE L1-L8: the gravity trick, so a resting contact sees the velocity gravity is about to
  // add, then one contact point per collision and the Newtonian impulse there.
  const Vec3 deltaV = gravityVelocity(world, gravity, dt);
  // A geometrically stable body's vertical momentum is reset below, so each pass's impulse on
  // its contacts is a new estimate of the support, not an increment of it.
  const auto isStable = [&](int i) { return !stable.empty() && stable[i] && !world.bodies[i].immovable; };
  const double j = impulseWithGravity(a, b, contact, restitution, deltaV, totals,
                                      isStable(contact.a) || isStable(contact.b));
  // COLLIDE L9-L10.
  addVelocity(a, -deltaV);
  addVelocity(b, -deltaV);
  // COLLIDE L9, L11-L14: a geometrically stable body neither rises nor tips.
  for (RigidBody* body : {&a, &b}) {
    const int index = body == &a ? contact.a : contact.b;
    if (stable.empty() || !stable[index] || body->immovable) continue;
    body->s.P.y() = 0.0;
    body->s.L.x() = 0.0;
    body->s.L.z() = 0.0;
    body->updateVelocities();
  }
  return j;
}

double approachSpeed(const World& world, const ImpulseContact& contact, GravityMode gravity,
                     double dt) {
  const RigidBody& a = world.bodies[contact.a];
  const RigidBody& b = world.bodies[contact.b];
  // The gravity trick of COLLIDE L1-L6: g Δt is added to movable bodies only, so it cancels
  // between two movable ones.
  const Vec3 deltaV = gravityVelocity(world, gravity, dt);
  return -relativeNormalVelocity(a, b, contact.ra, contact.rb, contact.normal) -
         contact.normal.dot((b.immovable ? Vec3(Vec3::Zero()) : deltaV) -
                            (a.immovable ? Vec3(Vec3::Zero()) : deltaV));
}

double collideImpulse(const World& world, const ImpulseContact& contact, double restitution,
                      GravityMode gravity, double dt) {
  RigidBody a = world.bodies[contact.a];
  RigidBody b = world.bodies[contact.b];
  return impulseWithGravity(a, b, contact, restitution, gravityVelocity(world, gravity, dt), nullptr,
                            false);
}

PassResult impulsePass(World& world, double dt, double restitution, GravityMode predict,
                       GravityMode impulseGravity, double margin, ContactGathering& gathering,
                       const std::vector<char>& stable, std::vector<char>* touched,
                       const BeforeCollide& beforeCollide, FrictionTotals* totals,
                       IslandSettling settling) {
  // RESOLVECOLLISIONS L2-L3, L6 and RESOLVECONTACTS L2-L3, L6: integrateObjectPositions and
  // gatherCollisions, and revertToOriginalPositions too: the contacts keep the lever arms of
  // the poses they were found at.
  // DEVIATION(RESOLVECOLLISIONS L4-L6, RESOLVECONTACTS L4-L6): COLLIDE after the revert
  // (contact_gathering.hpp, "Where COLLIDE acts").
  std::vector<ImpulseContact>& contacts = gathering.begin(world, dt, predict, margin);
  // RESOLVECOLLISIONS L4-L5 and RESOLVECONTACTS L4-L5: collide every pair.
  PassResult result;
  result.contacts = static_cast<int>(contacts.size());
  const CollideCall call{restitution, impulseGravity, dt};
  // The weight stable bodies put on their frictional supports, friction's budget for them.
  if (totals) totals->shareWeights(world, contacts, stable, dt);
  // The pass' contacts are those of the islands still active (contact_islands.hpp).
  ContactIslands* islands = settling == IslandSettling::Never ? nullptr : gathering.islands();
  for (ImpulseContact& c : contacts) {
    // The island of the contact's movable body (a movable body's island holds both).
    const int body = world.bodies[c.a].immovable ? c.b : c.a;
    // Once one contact changed a body the pass has changed the world: no more comparing,
    // unless the islands need to know which.
    const bool watch = !result.changed || (islands && !islands->changed(body));
    const BodyMomenta beforeA(world.bodies[c.a]), beforeB(world.bodies[c.b]);
    if (beforeCollide) beforeCollide(world, c, call);
    if (touched) (*touched)[c.a] = (*touched)[c.b] = 1;
    const double j = collide(world, c, restitution, impulseGravity, dt, stable, totals);
    if (j > 0.0) ++result.impulses;
    if (!watch) continue;
    const bool changed = !beforeA.same(world.bodies[c.a]) || !beforeB.same(world.bodies[c.b]);
    result.changed = result.changed || changed;
    if (islands && (changed || (settling == IslandSettling::Unapproached && j > 0.0)))
      islands->markChanged(body);
  }
  if (islands) result.settled = islands->settleUnchanged();
  // The momenta the impulses changed stay.
  gathering.end(world);
  return result;
}

void integrateVelocities(World& world, double dt) {
  for (RigidBody& body : world.bodies)
    if (!body.immovable) {
      body.s.P += dt * body.mass * world.gravity;
      body.updateVelocities();
    }
}

double restingContactMargin(const World& world, double margin, double dt) {
  return margin + world.gravity.norm() * dt * dt;
}

std::map<std::string, std::string> impulseParameters(const ImpulseParams& params) {
  return {{"collision_iterations", std::to_string(params.collisionIterations)},
          {"contact_iterations", std::to_string(params.contactIterations)},
          {"contact_normal", contactNormalModelName(params.normalModel)},
          {"contact_margin_per_l", shortestText(params.contactMargin)},
          {"contact_gathering", contactGatheringName(params.gathering)},
          {"slow_widening_per_l", shortestText(params.slowWidening)},
          {"exact_reach_per_l", shortestText(params.exactReach)},
          {"pair_reach", params.pairReach ? "on" : "off"},
          {"common_lever_point", params.commonLeverPoint ? "on" : "off"},
          {"integrator", integratorName(params.integrator)}};
}

double smallestHalfExtent(const World& world) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const RigidBody& b : world.bodies)
    if (!b.immovable) smallest = std::min(smallest, b.halfExtents.minCoeff());
  return std::isfinite(smallest) ? smallest : 1.0;
}

}  // namespace boxsim
