/// \file
/// COLLIDE and the predict–gather–collide–revert pass of \alg{A.2}.
#include "boxsim/impulse_damped/impulse_pass.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/core/newtonian_impulse.hpp"
#include "boxsim/impulse_damped/openmp.hpp"

namespace boxsim {

void addVelocity(RigidBody& body, const Vec3& deltaV) {
  if (body.immovable) return;
  body.s.P += body.mass * deltaV;
  body.v = body.invMass * body.s.P;  // L is unchanged, so ω = I⁻¹ L is too
}

void holdGeometricallyStable(RigidBody& body) {
  body.s.P.y() = 0.0;
  body.s.L.x() = 0.0;
  body.s.L.z() = 0.0;
  body.updateVelocities();
}

namespace {

/// What COLLIDE may change of a body, to tell whether it did, bit for bit.
struct BodyMomenta {
  Vec3 P, L;
  bool immovable;
  explicit BodyMomenta(const RigidBody& body) : P(body.s.P), L(body.s.L), immovable(body.immovable) {}
  bool same(const RigidBody& body) const {
    return sameBits(P, body.s.P) && sameBits(L, body.s.L) && immovable == body.immovable;
  }
};

/// What COLLIDE may change of a pair's friction sums, to tell whether it did, bit for bit.
struct SumBits {
  double normal = 0.0, torsional = 0.0;
  Vec3 tangential = Vec3::Zero(), couple = Vec3::Zero();
  SumBits() = default;
  explicit SumBits(const FrictionSum& sum)
      : normal(sum.normal),
        torsional(sum.torsional),
        tangential(sum.tangential),
        couple(sum.couple) {}
  bool same(const FrictionSum& sum) const {
    return sameBits(normal, sum.normal) && sameBits(torsional, sum.torsional) &&
           sameBits(tangential, sum.tangential) && sameBits(couple, sum.couple);
  }
};

/// COLLIDE L5-L6, L8: both bodies get deltaV, then the Newtonian impulse at the contact (its
/// point found by COLLIDE L7, ContactNormalTracker::contactOf); returns j.
double impulseWithGravity(RigidBody& a, RigidBody& b, const ImpulseContact& contact,
                          double restitution, const Vec3& deltaV, FrictionTotals* totals,
                          bool restarted, bool supportA, bool supportB, FrictionSum* sum) {
  addVelocity(a, deltaV);
  addVelocity(b, deltaV);
  return contactImpulse(a, b, contact, restitution, totals, restarted, supportA, supportB, sum);
}
}  // namespace

double contactImpulse(RigidBody& a, RigidBody& b, const ImpulseContact& contact, double restitution,
                      FrictionTotals* totals, bool restarted, bool supportA, bool supportB,
                      FrictionSum* given) {
  if (contact.friction.frictionless())
    return applyNewtonianImpulse(a, b, contact.ra, contact.rb, contact.normal, restitution,
                                 supportA, supportB);
  // A sum of its own only for a contact with neither (its rows are a kilobyte to clear).
  std::optional<FrictionSum> alone;
  FrictionSum& sum = given ? *given : totals ? totals->at(contact.a, contact.b) : alone.emplace();
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
  const double share = totals ? totals->supportShare(contact) : 0.0;
  // m/s: how fast the pair approaches at the contact now (negative: parting); read by the
  // resting test here and the impact test below.
  const double approach =
      totals ? -relativeNormalVelocity(a, b, contact.ra, contact.rb, contact.normal) : 0.0;
  if (share > impulses) {
    const bool resting = approach >= 0.0 && approach <= totals->restingSpeed();
    if (restarted || resting) sum.normal = share;
  }
  // An impact: a contact with no budget yet in the step (no normal impulse, no load it carries)
  // that approaches faster than gravity's g Δt. Its friction's budget is the normal impulse the
  // impact is about to get, Coulomb's law of impact (friction within μ times the impact's
  // normal impulse), and not the tipping couple, which is a resting patch's. On the passes
  // before alone it had none, and a pair that bounced apart is not gathered again: a cube landing
  // on frictional ground kept its horizontal speed through every bounce.
  if (sum.normal == 0.0 && !restarted && totals && approach > totals->restingSpeed()) {
    const double k = pairInverseMass(a, b, contact.ra, contact.rb, contact.normal);
    if (k > 0.0) sum.normal = (1.0 + restitution) * approach / k;
    patch.count = 0;
  }
  applyPatchFriction(a, b, contact.ra, contact.rb, contact.normal, contact.friction, patch, sum);
  sum.normal = impulses;
  const double j = applyNewtonianImpulse(a, b, contact.ra, contact.rb, contact.normal, restitution,
                                         supportA, supportB);
  sum.normal = restarted ? std::max(sum.normal, j) : sum.normal + j;
  return j;
}

double collide(World& world, const ImpulseContact& contact, double restitution, GravityMode gravity,
               double dt, const std::vector<char>& stable, FrictionTotals* totals,
               FrictionSum* sum) {
  RigidBody& a = world.bodies[contact.a];
  RigidBody& b = world.bodies[contact.b];
  // COLLIDE L1-L8: the gravity trick, so a resting contact sees the velocity gravity is about to
  // add, then one contact point per collision and the Newtonian impulse there.
  const Vec3 deltaV = gravityVelocity(world, gravity, dt);
  // A geometrically stable body's vertical momentum is reset below, so each pass's impulse on
  // its contacts is a new estimate of the support, not an increment of it.
  const auto isStable = [&](int i) { return !stable.empty() && stable[i] && !world.bodies[i].immovable; };
  // A stable body under the other one carries it (applyNewtonianImpulse's supports): n points
  // from a to b, so a is below when n points up. Two stable bodies, or a stable body and an
  // immovable one, take A.2's impulse.
  const bool stableA = isStable(contact.a), stableB = isStable(contact.b);
  bool supportA = false, supportB = false;
  if (stableA != stableB) {
    const double up = -contact.normal.dot(world.gravity);
    supportA = stableA && !b.immovable && up > 0.0;
    supportB = stableB && !a.immovable && up < 0.0;
  }
  const double j = impulseWithGravity(a, b, contact, restitution, deltaV, totals,
                                      stableA || stableB, supportA, supportB, sum);
  // COLLIDE L9-L10.
  addVelocity(a, -deltaV);
  addVelocity(b, -deltaV);
  // COLLIDE L9, L11-L14: a geometrically stable body neither rises nor tips.
  for (RigidBody* body : {&a, &b}) {
    const int index = body == &a ? contact.a : contact.b;
    if (stable.empty() || !stable[index] || body->immovable) continue;
    holdGeometricallyStable(*body);
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
                            false, false, false, nullptr);
}

namespace {

/// Whether COLLIDE's contact, approaching at `approach` m/s before it, was an impact
/// (PassResult::impacts): an impulse `j` > 0 and approach Δt above `reach` ℓ.
bool isImpact(const World& world, const ImpulseContact& c, double approach, double j, double dt,
              double reach) {
  const double ell = std::min(world.bodies[c.a].halfExtents.minCoeff(),
                              world.bodies[c.b].halfExtents.minCoeff());
  return j > 0.0 && approach * dt > reach * ell;
}

/// Whether COLLIDE's loop of a pass may run in dependency levels on several threads (the
/// conditions of impulsePass' "Threads", the threads aside).
bool levelsApply(const World& world, const std::vector<ImpulseContact>& contacts,
                 const ContactGathering& gathering, const BeforeCollide& beforeCollide) {
  if (contacts.size() < 2) return false;
  if (!beforeCollide) return true;
  const std::vector<char>* asleep = gathering.sleepers();
  if (!asleep || asleep->size() != world.bodies.size()) return false;
  for (const ImpulseContact& c : contacts)
    if ((*asleep)[c.a] != (*asleep)[c.b]) return false;
  return true;
}

/// A frictional contact's COLLIDE costs about this many frictionless ones (applyPatchFriction's
/// five rows), for the work per level that ImpulseParams::parallelContacts asks for.
constexpr int kFrictionalWork = 4;

/// The dependency levels of the pass' contacts into w.level, w.body, w.start and w.byLevel (the
/// contacts of level l are w.byLevel[w.start[l], w.start[l + 1]), in their order); returns
/// whether the work per level, in frictionless contacts (kFrictionalWork), reaches
/// `parallelContacts`.
bool findLevels(const World& world, const std::vector<ImpulseContact>& contacts,
                int parallelContacts, CollideLevels& w) {
  const std::size_t n = world.bodies.size(), m = contacts.size();
  // Each contact's level: one more than the deepest level of the contacts before it on either
  // of its movable bodies. No contact of the pass wakes a sleeper (levelsApply), so the bodies
  // immovable now stay so, and only read, through the pass.
  w.lastLevel.assign(n, 0);
  w.level.resize(m);
  w.body.resize(m);
  int levels = 0;
  long work = 0;
  for (std::size_t k = 0; k < m; ++k) {
    const ImpulseContact& c = contacts[k];
    work += c.friction.frictionless() ? 1 : kFrictionalWork;
    const bool movableA = !world.bodies[c.a].immovable, movableB = !world.bodies[c.b].immovable;
    int level = 0;
    if (movableA) level = std::max(level, w.lastLevel[c.a]);
    if (movableB) level = std::max(level, w.lastLevel[c.b]);
    if (movableA) w.lastLevel[c.a] = level + 1;
    if (movableB) w.lastLevel[c.b] = level + 1;
    w.level[k] = level;
    levels = std::max(levels, level + 1);
    // The island is the movable body's, as the loop in order reads it before COLLIDE.
    w.body[k] = movableA ? c.a : c.b;
  }
  // A counting sort by level; contacts keep their order within a level.
  w.start.assign(static_cast<std::size_t>(levels) + 1, 0);
  for (std::size_t k = 0; k < m; ++k) ++w.start[static_cast<std::size_t>(w.level[k]) + 1];
  for (int l = 0; l < levels; ++l) w.start[l + 1] += w.start[l];
  w.next.assign(w.start.begin(), w.start.end() - 1);
  w.byLevel.resize(m);
  for (std::size_t k = 0; k < m; ++k) w.byLevel[w.next[w.level[k]]++] = static_cast<int>(k);
  return work >= static_cast<long>(parallelContacts) * levels;
}

/// COLLIDE's loop of impulsePass in dependency levels (its "Threads"), the levels found by
/// findLevels: the same PassResult, world, sums, islands and `touched` flags as the loop in
/// order, bit for bit. The working lists are the caller's, kept from pass to pass.
void collideInLevels(World& world, std::vector<ImpulseContact>& contacts, const CollideCall& call,
                     const std::vector<char>& stable, std::vector<char>* touched,
                     const BeforeCollide& beforeCollide, FrictionTotals* totals,
                     ContactIslands* islands, IslandSettling settling, [[maybe_unused]] int threads,
                     CollideLevels& w, double impactReach, PassResult& result) {
  const std::size_t m = contacts.size();
  const int levels = static_cast<int>(w.start.size()) - 1;
  // The pairs' friction sums inserted first, then their addresses taken (an insertion may move
  // the values): the threads only look at their own pair's sums.
  w.sums.assign(m, nullptr);
  if (totals) {
    for (const ImpulseContact& c : contacts)
      if (!c.friction.frictionless()) totals->at(c.a, c.b);
    for (std::size_t k = 0; k < m; ++k)
      if (!contacts[k].friction.frictionless())
        w.sums[k] = &totals->at(contacts[k].a, contacts[k].b);
  }
  if (touched)
    for (const ImpulseContact& c : contacts) (*touched)[c.a] = (*touched)[c.b] = 1;
  w.impulse.assign(m, 0.0);
  w.changed.assign(m, 0);
  if (impactReach > 0.0) w.impact.assign(m, 0);
  BOXSIM_OMP(omp parallel num_threads(threads))
  for (int l = 0; l < levels; ++l) {
    // The contacts of a level share no movable body: in any order, the same bits.
    BOXSIM_OMP(omp for schedule(static))
    for (int p = w.start[l]; p < w.start[l + 1]; ++p) {
      const std::size_t k = static_cast<std::size_t>(w.byLevel[p]);
      ImpulseContact& c = contacts[k];
      const BodyMomenta beforeA(world.bodies[c.a]), beforeB(world.bodies[c.b]);
      const SumBits sumBefore = w.sums[k] ? SumBits(*w.sums[k]) : SumBits();
      if (beforeCollide) beforeCollide(world, c, call);
      const double approach =
          impactReach > 0.0 ? approachSpeed(world, c, call.gravity, call.dt) : 0.0;
      w.impulse[k] =
          collide(world, c, call.restitution, call.gravity, call.dt, stable, totals, w.sums[k]);
      if (impactReach > 0.0)
        w.impact[k] =
            static_cast<char>(isImpact(world, c, approach, w.impulse[k], call.dt, impactReach));
      w.changed[k] = static_cast<char>(!beforeA.same(world.bodies[c.a]) ||
                                       !beforeB.same(world.bodies[c.b]) ||
                                       (w.sums[k] && !sumBefore.same(*w.sums[k])));
    }
  }
  // What the loop in order counts and marks, in its order.
  for (std::size_t k = 0; k < m; ++k) {
    if (w.impulse[k] > 0.0) ++result.impulses;
    result.changed = result.changed || w.changed[k];
    const bool approached = settling == IslandSettling::Unapproached && w.impulse[k] > 0.0;
    if (islands && (w.changed[k] || approached)) islands->markChanged(w.body[k]);
    if (impactReach > 0.0 && w.impact[k]) ++result.impacts;
  }
}

/// COLLIDE's loop of impulsePass in A.2's order, contact after contact: its PassResult
/// (impulses, whether anything changed) and the islands the contacts changed; with kImpacts, its
/// impacts (PassResult::impacts) of `impactReach` ℓ per Δt (a template argument, so that the
/// passes that count none carry no test of it).
template <bool kImpacts>
void collideInOrder(World& world, std::vector<ImpulseContact>& contacts, const CollideCall& call,
                    const std::vector<char>& stable, std::vector<char>* touched,
                    const BeforeCollide& beforeCollide, FrictionTotals* totals,
                    ContactIslands* islands, IslandSettling settling, double impactReach,
                    PassResult& result) {
  for (ImpulseContact& c : contacts) {
    // The island of the contact's movable body (a movable body's island holds both).
    const int body = world.bodies[c.a].immovable ? c.b : c.a;
    // Once one contact changed a body the pass has changed the world: no more comparing,
    // unless the islands need to know which.
    const bool watch = !result.changed || (islands && !islands->changed(body));
    const BodyMomenta beforeA(world.bodies[c.a]), beforeB(world.bodies[c.b]);
    // The pair's friction sums, looked up once and handed to COLLIDE.
    FrictionSum* sum = totals && !c.friction.frictionless() ? &totals->at(c.a, c.b) : nullptr;
    const SumBits sumBefore = watch && sum ? SumBits(*sum) : SumBits();
    if (beforeCollide) beforeCollide(world, c, call);
    if (touched) (*touched)[c.a] = (*touched)[c.b] = 1;
    double approach = 0.0;
    if constexpr (kImpacts) approach = approachSpeed(world, c, call.gravity, call.dt);
    const double j = collide(world, c, call.restitution, call.gravity, call.dt, stable, totals, sum);
    if (j > 0.0) ++result.impulses;
    if constexpr (kImpacts)
      if (isImpact(world, c, approach, j, call.dt, impactReach)) ++result.impacts;
    if (!watch) continue;
    // With friction, the pair's sums (FrictionTotals) are state too, which the momenta do not
    // show: an impulse too small to change them, or one COLLIDE L11-L14 takes back, still grows
    // the budget, and a friction increment below their rounding still adds to the sums.
    const bool changed = !beforeA.same(world.bodies[c.a]) || !beforeB.same(world.bodies[c.b]) ||
                         (sum && !sumBefore.same(*sum));
    result.changed = result.changed || changed;
    if (islands && (changed || (settling == IslandSettling::Unapproached && j > 0.0)))
      islands->markChanged(body);
  }
}

}  // namespace

PassResult impulsePass(World& world, double dt, double restitution, GravityMode predict,
                       GravityMode impulseGravity, double margin, ContactGathering& gathering,
                       const std::vector<char>& stable, std::vector<char>* touched,
                       const BeforeCollide& beforeCollide, FrictionTotals* totals,
                       IslandSettling settling, double impactReach) {
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
  // The weight bodies put on their frictional supports, friction's least budget for them.
  if (totals) totals->shareWeights(world, contacts, dt);
  // The pass' contacts are those of the islands still active (contact_islands.hpp).
  ContactIslands* islands = settling == IslandSettling::Never ? nullptr : gathering.islands();
  // Levels are found when threads may share them, or when their work is measured.
  ParallelWork* work = gathering.parallelWork();
  const bool shared =
      (gathering.threads() > 1 || work) && levelsApply(world, contacts, gathering, beforeCollide) &&
      findLevels(world, contacts, gathering.parallelContacts(), gathering.collideLevels());
  const auto start = ParallelWork::startOf(work);
  if (shared && gathering.threads() > 1) {
    gathering.countLevelPass();
    collideInLevels(world, contacts, call, stable, touched, beforeCollide, totals, islands,
                    settling, gathering.threads(), gathering.collideLevels(), impactReach, result);
  } else {
    if (impactReach > 0.0)
      collideInOrder<true>(world, contacts, call, stable, touched, beforeCollide, totals, islands,
                           settling, impactReach, result);
    else
      collideInOrder<false>(world, contacts, call, stable, touched, beforeCollide, totals, islands,
                            settling, impactReach, result);
  }
  if (work && shared) {
    ParallelWork::addSince(work->levelSeconds, start);
    const std::vector<int>& levelStart = gathering.collideLevels().start;
    for (std::size_t l = 0; l + 1 < levelStart.size(); ++l)
      ParallelWork::countLoop(work->levelRounds, levelStart[l + 1] - levelStart[l]);
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
          {"predicted_anchor", params.predictedAnchor ? "on" : "off"},
          {"exact_edge_pairs", params.exactEdgePairs ? "on" : "off"},
          {"edge_corners", params.edgeCorners ? "on" : "off"},
          {"common_lever_point", params.commonLeverPoint ? "on" : "off"},
          {"integrator", integratorName(params.integrator)},
          {"threads", std::to_string(params.threads)}};
}

double smallestHalfExtent(const World& world) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const RigidBody& b : world.bodies)
    if (!b.immovable) smallest = std::min(smallest, b.halfExtents.minCoeff());
  return std::isfinite(smallest) ? smallest : 1.0;
}

}  // namespace boxsim
