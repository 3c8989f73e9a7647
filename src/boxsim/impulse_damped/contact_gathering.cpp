/// \file
/// gatherCollisions at predicted positions (\alg{A.2}), every pass or once per step.
#include "boxsim/impulse_damped/contact_gathering.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <stdexcept>
#include <utility>

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/collision/contact_manifold.hpp"

namespace boxsim {

std::string contactGatheringName(ContactGatheringMode mode) {
  switch (mode) {
    case ContactGatheringMode::EveryPass: return "every_pass";
    case ContactGatheringMode::OncePerStep: return "once_per_step";
  }
  return "unknown";
}

ContactGatheringMode parseContactGathering(const std::string& name) {
  for (ContactGatheringMode m : {ContactGatheringMode::EveryPass, ContactGatheringMode::OncePerStep})
    if (contactGatheringName(m) == name) return m;
  throw std::invalid_argument("unknown contact gathering '" + name +
                              "'; use every_pass or once_per_step");
}

void movePredicted(RigidBody& body, double dt, const Vec3& extraVelocity,
                   Integrator integrator) {
  body.s.x += dt * (body.v + extraVelocity);
  if (integrator == Integrator::SplitRotation) {
    splitRotation(body, dt);
    return;
  }
  const Quat w(0.0, body.omega.x(), body.omega.y(), body.omega.z());
  body.s.q.coeffs() += (0.5 * dt) * (w * body.s.q).coeffs();
  body.s.q.normalize();
  body.updateDerived();
}

SavedPoses predictPositions(World& world, double dt, const Vec3& extraVelocity,
                            Integrator integrator) {
  SavedPoses saved;
  saved.reserve(world.bodies.size());
  for (RigidBody& body : world.bodies) {
    saved.push_back({body.s.x, body.s.q, body.R, body.Iinv, body.immovable});
    if (!body.immovable) movePredicted(body, dt, extraVelocity, integrator);
  }
  return saved;
}

void restorePose(RigidBody& body, const SavedPose& pose) {
  body.s.x = pose.x;
  body.s.q = pose.q;
  if (pose.immovable != body.immovable) {
    body.updateDerived();
    return;
  }
  body.R = pose.R;
  body.Iinv = pose.Iinv;
  body.updateVelocities();  // P and L may have changed while the body stood elsewhere
}

void revertPositions(World& world, const SavedPoses& saved) {
  for (std::size_t i = 0; i < world.bodies.size(); ++i) {
    // predictPositions leaves immovable bodies where they are; with many sleeping bodies
    // standing in as immovable (§4.5), recomputing their derived values was most of the work.
    if (world.bodies[i].immovable) continue;
    restorePose(world.bodies[i], saved[i]);
  }
}

ContactGathering::ContactGathering(const ImpulseParams& params)
    : params_(params), normals_(params.normalModel) {
  if (!(params.exactReach >= 0.0) || !std::isfinite(params.exactReach) ||
      !(params.slowWidening >= params.exactReach) || !std::isfinite(params.slowWidening))
    throw std::invalid_argument(
        "contact gathering: the exact reach must be a finite number >= 0 and the widening a "
        "finite number >= the exact reach (units of l)");
  if (params.integrator != Integrator::SemiImplicitEuler &&
      params.integrator != Integrator::SplitRotation)
    throw std::invalid_argument("the impulse-based step integrates with semi_implicit_euler or "
                                "split_rotation (its velocities come before its positions), not " +
                                integratorName(params.integrator));
}

double ContactGathering::reach(const RigidBody& body, const Vec3& gravityStep, double dt) const {
  if (body.immovable) return 0.0;
  return dt * ((body.v + gravityStep).norm() + body.omega.norm() * body.halfExtents.norm());
}

bool ContactGathering::cacheCovers(const World& world) const {
  if (!cached_ || immovable_.size() != world.bodies.size()) return false;
  for (std::size_t i = 0; i < world.bodies.size(); ++i)
    if (static_cast<char>(world.bodies[i].immovable) != immovable_[i]) return false;
  return true;
}


void ContactGathering::buildCache(const World& world, const Vec3& gravityStep, double dt,
                                  double margin) {
  const std::size_t n = world.bodies.size();
  std::vector<double> widening(n, 0.0);
  immovable_.assign(n, 0);
  if (fast_.size() != n) fast_.assign(n, 0);
  lo_.resize(n);
  hi_.resize(n);
  halfDiagonal_.resize(n);
  slowReach_.resize(n);
  passU_.resize(n);
  passTurn_.resize(n);
  passSpin_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const RigidBody& body = world.bodies[i];
    obbBounds(Obb::of(body), 0.0, lo_[i], hi_[i]);
    immovable_[i] = static_cast<char>(body.immovable);
    halfDiagonal_[i] = body.halfExtents.norm();
    slowReach_[i] = params_.exactReach * body.halfExtents.minCoeff();
    setPassMotion(body, static_cast<int>(i), gravityStep, dt);
    if (body.immovable) continue;
    widening[i] = params_.slowWidening * body.halfExtents.minCoeff();
    if (reach(body, gravityStep, dt) > params_.exactReach * body.halfExtents.minCoeff())
      fast_[i] = 1;
  }
  // Wider than the passes need: their own test (boundsWithin with `margin`) picks from the
  // candidates, so a wider sweep finds the same contacts, and it makes the candidates hold the
  // pairs FIXCONTACTCONSTRAINTS looks at after the passes (stepPairs), whose margin
  // (restingContactMargin) is wider by g Δt².
  sweepMargin_ = margin + world.gravity.norm() * dt * dt;
  guardScale_ = 1.0;
  pairs_.clear();
  pairReach_.clear();
  sweepCandidates(world, gravityStep, dt);
  // One narrow phase at the current poses for the slow pairs, each body widened by more than a
  // slow body can move (slowWidening >= exactReach): the pairs the broad phase
  // gives with margin and widening, picked from the candidates (whose growth is at least the
  // widening) by the sweep's own test.
  exactManifolds_.clear();
  for (Candidate& candidate : candidates_) {
    const int i = candidate.a, j = candidate.b;
    // Gathered as written, pass by pass, unless the two move together.
    const bool together = params_.pairReach && movingTogether(i, j);
    if ((fast_[i] || fast_[j]) && !together) continue;
    Vec3 loI, hiI, loJ, hiJ;
    obbBounds(Obb::of(world.bodies[i]), widening[i], loI, hiI);
    obbBounds(Obb::of(world.bodies[j]), widening[j], loJ, hiJ);
    if (!boundsWithin(loI, hiI, loJ, hiJ, margin)) continue;
    const double pairMargin = margin + widening[i] + widening[j];
    ContactManifold m = collideBoxes(Obb::of(world.bodies[i]), Obb::of(world.bodies[j]), pairMargin);
    // Closer than the margin along every axis, yet no point: boxes passing corner by corner.
    // The pair stays, with no points, and gets the exact narrow phase every pass.
    if (m.depth <= -pairMargin) continue;
    // A pair with a fast body is predicted from its points only: with none, it is gathered
    // as written.
    if ((fast_[i] || fast_[j]) && m.count == 0) continue;
    m.a = i;
    m.b = j;
    const Vec3& xa = world.bodies[i].s.x;
    const Vec3& xb = world.bodies[j].s.x;
    // The normal model's choice now; its face is remembered only in the passes the pair touches.
    CachedPair pair{normals_.contactOf(world, m, false), m, {}, 0, false};
    PairReach reachOf{i, j, 0};
    for (int k = 0; k < m.count; ++k) {
      const ContactPoint& p = m.points[k];
      const Vec3 ra = p.position - xa, rb = p.position - xb;
      pair.points[pair.count++] = CachedPoint{p.position, p.depth,       ra,          rb,
                                              ra.cross(m.normal), rb.cross(m.normal),
                                              m.normal.dot(ra),   m.normal.dot(rb)};
      reachOf.deepest = k == 0 ? p.depth : std::max(reachOf.deepest, p.depth);
      reachOf.leverA = std::max(reachOf.leverA, ra.norm());
      reachOf.leverB = std::max(reachOf.leverB, rb.norm());
    }
    reachOf.count = pair.count;
    candidate.cached = static_cast<int>(pairs_.size());
    pairs_.push_back(pair);
    pairReach_.push_back(reachOf);
  }
  ++narrowPhases_;
  // Every predicted pose and every candidate's answer is from before this build.
  buildStamp_ = ++stampCounter_;
  predicted_.resize(n);
  manifolds_.clear();
  cacheMargin_ = margin;
  cached_ = true;
}

void ContactGathering::setPassMotion(const RigidBody& body, int i, const Vec3& gravityStep,
                                     double dt) {
  passU_[i] = body.immovable ? body.v : Vec3(body.v + gravityStep);
  passSpin_[i] = body.omega.norm();
  passTurn_[i] = dt * passSpin_[i] * halfDiagonal_[i];
  passDt_ = dt;
}

bool ContactGathering::mayTouch(const PairReach& reach, double margin) const {
  const double dt = passDt_;
  // A point's depth changes in the pass by n · (d_a - d_b) (predictedContact), at most
  // Δt |v'_a - v'_b| + Δt |ω| |r| + Δt² |ω|² |r| for each body; the allowance relative to the
  // terms, far above their rounding, keeps the answer what the computed depths would give.
  const double wa = passSpin_[reach.a], wb = passSpin_[reach.b];
  const double bound = dt * (passU_[reach.a] - passU_[reach.b]).norm() +
                       dt * (wa * reach.leverA + wb * reach.leverB) +
                       dt * dt * (wa * wa * reach.leverA + wb * wb * reach.leverB);
  return reach.deepest + bound + 1e-12 * (std::abs(reach.deepest) + bound) > -margin;
}

bool ContactGathering::movingTogether(int a, int b) const {
  return passDt_ * (passU_[a] - passU_[b]).norm() + passTurn_[a] + passTurn_[b] <=
         std::min(slowReach_[a], slowReach_[b]);
}

bool ContactGathering::predictedTogether(const PairReach& reach) const {
  return reach.count > 0 && params_.pairReach && movingTogether(reach.a, reach.b);
}

bool ContactGathering::predictedContact(const World& world, const CachedPair& pair,
                                        const Vec3& gravityStep, double dt, double margin,
                                        ImpulseContact& contact) const {
  const RigidBody& a = world.bodies[pair.contact.a];
  const RigidBody& b = world.bodies[pair.contact.b];
  const Vec3 ua = a.immovable ? a.v : Vec3(a.v + gravityStep);
  const Vec3 ub = b.immovable ? b.v : Vec3(b.v + gravityStep);
  const Vec3& n = pair.manifold.normal;
  const double linear = n.dot(ua - ub);
  // n · (ω × (ω × r)) = (n · ω)(ω · r) - |ω|² (n · r), with n · r cached per point.
  const double nwa = n.dot(a.omega), nwb = n.dot(b.omega);
  const double wa2 = a.omega.squaredNorm(), wb2 = b.omega.squaredNorm();
  Vec3 sum = Vec3::Zero();
  int kept = 0;
  std::array<bool, 4> keptPoint{};
  double deepest = 0.0;
  for (int i = 0; i < pair.count; ++i) {
    const CachedPoint& p = pair.points[i];
    // n · (ω × r) = ω · (r × n).
    const double turning = a.omega.dot(p.raCrossN) - b.omega.dot(p.rbCrossN);
    const double centripetal = (nwa * a.omega.dot(p.ra) - wa2 * p.nDotRa) -
                               (nwb * b.omega.dot(p.rb) - wb2 * p.nDotRb);
    const double depth = p.depth + dt * (linear + turning) + (0.5 * dt * dt) * centripetal;
    if (depth <= -margin) continue;
    keptPoint[i] = true;
    deepest = kept == 0 ? depth : std::max(deepest, depth);
    sum += p.position;
    ++kept;
  }
  if (kept == 0) return false;
  contact = pair.contact;
  contact.point = sum / static_cast<double>(kept);
  if (!contact.friction.frictionless()) {
    // The friction patch is the kept points, about the new centroid, in the order around the
    // patch that the found contact gave them (a subset of a convex outline stays one).
    const ContactPatch& found = pair.contact.patch;
    contact.patch.count = 0;
    for (int k = 0; k < found.count; ++k) {
      const int i = found.pointOf[k];
      if (!keptPoint[i]) continue;
      contact.patch.offsets[contact.patch.count] = pair.points[i].position - contact.point;
      contact.patch.pointOf[contact.patch.count++] = i;
    }
  }
  contact.depth = deepest;
  contact.ra = contact.point - a.s.x;
  contact.rb = contact.point - b.s.x;
  return true;
}

void ContactGathering::preparePredicted(const RigidBody& body, int i, double dt,
                                        const Vec3& gravityStep) {
  PredictedPose& p = predicted_[i];
  // movePredicted reads x, q (unchanged since the build), v and ω; the velocities it leaves
  // come from P and L: with all of them as before, it would compute the same pose, bit for bit.
  if (p.stamp > buildStamp_ && sameBits(p.v, body.v) && sameBits(p.omega, body.omega) &&
      sameBits(p.P, body.s.P) && sameBits(p.L, body.s.L))
    return;
  RigidBody moved = body;
  movePredicted(moved, dt, gravityStep);
  p.P = body.s.P;
  p.L = body.s.L;
  p.v = body.v;
  p.omega = body.omega;
  p.x = moved.s.x;
  p.q = moved.s.q;
  p.R = moved.R;
  p.Iinv = moved.Iinv;
  p.vPredicted = moved.v;
  p.omegaPredicted = moved.omega;
  obbBounds(Obb::of(moved), 0.0, p.lo, p.hi);
  p.stamp = ++stampCounter_;
}

void ContactGathering::place(World& world, int i) {
  if (placed_[i] || !(moved_[i] || partner_[i])) return;
  RigidBody& body = world.bodies[i];
  const PredictedPose& p = predicted_[i];
  saved_[i] = SavedPose{body.s.x, body.s.q, body.R, body.Iinv, false};
  body.s.x = p.x;
  body.s.q = p.q;
  body.R = p.R;
  body.Iinv = p.Iinv;
  body.v = p.vPredicted;
  body.omega = p.omegaPredicted;
  placed_[i] = 1;
}

Obb ContactGathering::passBox(const World& world, int i) const {
  const RigidBody& body = world.bodies[i];
  if (!(moved_[i] || partner_[i])) return Obb::of(body);
  return Obb{predicted_[i].x, predicted_[i].R, body.halfExtents};
}

bool ContactGathering::contactOf(const World& world, int i, int j, ContactManifold m,
                                 ImpulseContact& contact) {
  if (m.count == 0) return false;
  m.a = i;
  m.b = j;
  contact = normals_.contactOf(world, m);
  return true;
}

std::vector<ImpulseContact>& ContactGathering::begin(World& world, double dt, GravityMode predict,
                                                     double margin) {
  std::vector<ImpulseContact>& contacts = gather(world, dt, predict, margin);
  if (!params_.commonLeverPoint) return contacts;
  // ImpulseParams::commonLeverPoint: both impulses act at one point, the midpoint of the
  // material points x + r' the found lever arms name at the current poses, so ±J exert no net
  // torque about any fixed point.
  for (ImpulseContact& c : contacts) {
    const Vec3& xa = world.bodies[c.a].s.x;
    const Vec3& xb = world.bodies[c.b].s.x;
    const Vec3 q = 0.5 * ((xa + c.ra) + (xb + c.rb));
    c.ra = q - xa;
    c.rb = q - xb;
  }
  return contacts;
}

void ContactGathering::beginStep(const World& world, double dt, GravityMode predict,
                                 double margin) {
  if (params_.gathering != ContactGatheringMode::OncePerStep) return;
  const Vec3 gravityStep = gravityVelocity(world, predict, dt);
  if (margin != cacheMargin_ || !cacheCovers(world)) buildCache(world, gravityStep, dt, margin);
}

std::vector<ImpulseContact>& ContactGathering::gather(World& world, double dt, GravityMode predict,
                                                      double margin) {
  const Vec3 gravityStep = gravityVelocity(world, predict, dt);
  if (params_.gathering == ContactGatheringMode::EveryPass) {
    // A.2 L2: integrateObjectPositions, remembering where every body was; L3: gatherCollisions.
    saved_ = predictPositions(world, dt, gravityStep);
    contacts_ = normals_.contactsOf(world, findContacts(world, margin));
    // DEVIATION(A.2 RESOLVECOLLISIONS/RESOLVECONTACTS L6): revertToOriginalPositions comes
    // before COLLIDE (see the file comment, "Where COLLIDE acts").
    revertPositions(world, saved_);
    return contacts_;
  }
  // DEVIATION(A.2 L2-L3): the prediction of the file comment.
  if (margin != cacheMargin_ || !cacheCovers(world)) buildCache(world, gravityStep, dt, margin);
  // The predicted poses kept are for one g Δt and Δt (a shock propagation pass, say, predicts
  // with another): for others they, and the answers found with them, are forgotten.
  if (!sameBits(gravityStep, predictedGravity_) ||
      !sameBits(dt, predictedDt_)) {
    predictedGravity_ = gravityStep;
    predictedDt_ = dt;
    buildStamp_ = ++stampCounter_;
  }
  // A.2 L2 for the fast bodies only: they go to their predicted poses, as written. A body fast
  // when the cache was built stays fast for the step: the cache holds only its pairs that
  // moved together then, predicted while they still do.
  const std::size_t n = world.bodies.size();
  moved_.assign(n, 0);
  placed_.assign(n, 0);
  partner_.assign(n, 0);
  saved_.resize(n);
  std::vector<int>& fast = fastBodies_;
  std::vector<int>& outgrown = outgrown_;
  fast.clear();
  outgrown.clear();
  passReach_.assign(n, 0.0);
  motion_.resize(n);
  // The bodies of settled islands sit this pass out (contact_islands.hpp): they would stand,
  // move and touch as in the pass that settled them, and change nothing.
  refreshIslands(world);
  skip_.resize(n);
  bool anySkipped = false;
  for (std::size_t i = 0; i < n; ++i) {
    skip_[i] = static_cast<char>(islands_.settled(static_cast<int>(i)));
    anySkipped = anySkipped || skip_[i];
  }
  const auto classify = [&](std::size_t i) {
    const RigidBody& body = world.bodies[i];
    // Reach and guard test depend on v and ω alone (and on the guard): with both bitwise as in
    // the last pass they are what they were then.
    PassMotion& motion = motion_[i];
    if (!(motion.stamp > buildStamp_ && sameBits(motion.v, body.v) &&
          sameBits(motion.omega, body.omega))) {
      motion.v = body.v;
      motion.omega = body.omega;
      // reach(), with the half diagonal and the bar of the slow bodies kept since the build.
      const Vec3 u = body.v + gravityStep;
      motion.turn = dt * body.omega.norm() * halfDiagonal_[i];
      motion.reach = dt * (u.norm() + body.omega.norm() * halfDiagonal_[i]);
      motion.guardStamp = 0;
      motion.stamp = ++stampCounter_;
    }
    const double r = motion.reach;
    passReach_[i] = r;
    if (!fast_[i] && r <= slowReach_[i]) return;
    fast.push_back(static_cast<int>(i));
    if (motion.guardStamp != guardStamp_[i]) {
      const Vec3 u = body.v + gravityStep;
      motion.withinGuard = withinGuard(body, static_cast<int>(i), Vec3(dt * u), motion.turn);
      motion.guardStamp = guardStamp_[i];
    }
    if (!motion.withinGuard) outgrown.push_back(static_cast<int>(i));
  };
  for (std::size_t i = 0; i < n; ++i) {
    setPassMotion(world.bodies[i], static_cast<int>(i), gravityStep, dt);
    if (!world.bodies[i].immovable && !skip_[i]) classify(i);
  }
  // The step's candidates hold every pair that can come near while each body moves less than
  // its growth; one that outgrew it needs its pairs found afresh, from the poses the bodies
  // stand at. A pair found so may join a settled island to an active one, which takes it up
  // again in this very pass.
  while (!outgrown.empty()) {
    growCandidates(world, gravityStep, dt, outgrown);
    outgrown.clear();
    if (!anySkipped) break;
    refreshIslands(world);
    anySkipped = false;
    for (std::size_t i = 0; i < n; ++i) {
      if (!skip_[i]) continue;
      if (islands_.settled(static_cast<int>(i))) {
        anySkipped = true;
      } else {
        skip_[i] = 0;
        classify(i);
      }
    }
  }
  if (anySkipped)
    for (std::size_t i = 0; i < n; ++i) skippedBodyPasses_ += skip_[i];
  islands_.flatten();
  bool anyFast = false;
  for (int i : fast) {
    RigidBody& body = world.bodies[i];
    // A fast body with no candidate cannot touch anything in this pass: its predicted pose
    // would be looked at by no one, so it stays, with the velocities putting it back recomputes.
    if (!hasCandidate_[i]) {
      body.updateVelocities();
      continue;
    }
    // It stands at its predicted pose for the pass (moved_); the narrow phase looks at that
    // pose where it is kept (passBox), and the body goes there (place) only when one of its
    // pairs touches: then the normal model and COLLIDE see it there, as written. A body that
    // touches nothing ends the pass as if it had gone and come back (end()).
    moved_[i] = 1;
    anyFast = true;
    preparePredicted(body, i, dt, gravityStep);
  }
  // A.2 L3 for the pairs with a fast body: the broad and narrow phase where the bodies now
  // stand, as written. The broad phase is the broad phases' own test (boundsWithin) on the
  // candidates, so it keeps the pairs a sweep at these poses would find, in the same (a, b)
  // order, which is the cache's order too, so the two lists merge into one.
  partners_.clear();
  poseStamp_.resize(n);
  for (std::size_t i = 0; i < n; ++i) poseStamp_[i] = moved_[i] ? predicted_[i].stamp : buildStamp_;
  fastContacts_.clear();
  ImpulseContact c;
  if (anyFast)
    for (std::size_t k = 0; k < candidates_.size(); ++k) {
      const int a = candidates_[k].a, b = candidates_[k].b;
      if (!moved_[a] && !moved_[b]) continue;
      // Two bodies moving together: predicted with the cached pairs below.
      const int cached = candidates_[k].cached;
      if (cached >= 0 && predictedTogether(pairReach_[static_cast<std::size_t>(cached)])) continue;
      // A.2 L2 for a moved body's slow partner too, as written, so the narrow phase sees both
      // where the pass predicts them. It moves by at most its reach, so if its bounds stay
      // farther than that plus the margin from the moved body's, the pair cannot touch in the
      // pass and it need not move for this pair (its current bounds then fail the test below
      // as its predicted ones would). It goes back before COLLIDE, below.
      if (moved_[a] != moved_[b]) {
        const int i = moved_[a] ? a : b, j = moved_[a] ? b : a;
        RigidBody& body = world.bodies[j];
        if (!body.immovable && !partner_[j]) {
          if (boundsWithin(predicted_[i].lo, predicted_[i].hi, lo_[j], hi_[j],
                           margin + passReach_[j] + roundingSlack(body, halfDiagonal_[j]))) {
            partner_[j] = 1;
            partners_.push_back(j);
            preparePredicted(body, j, dt, gravityStep);
            poseStamp_[j] = predicted_[j].stamp;
          }
        }
      }
      // Both bodies where they stood when the pair was last looked at: the broad and narrow
      // phase would answer as then, so the answer is taken from then (the normal model still
      // sees the manifold, as it would).
      Candidate& candidate = candidates_[k];
      const std::uint64_t stampA = poseStamp_[a], stampB = poseStamp_[b];
      if (candidate.stampA == stampA && candidate.stampB == stampB) {
        if (candidate.manifold >= 0) {
          place(world, a);
          place(world, b);
          if (contactOf(world, a, b, manifolds_[static_cast<std::size_t>(candidate.manifold)], c))
            fastContacts_.push_back(c);
        }
        continue;
      }
      candidate.stampA = stampA;
      candidate.stampB = stampB;
      // Bounds where each body stands in this pass: predicted once it moved, current before.
      const bool predictedA = moved_[a] || partner_[a], predictedB = moved_[b] || partner_[b];
      const Vec3& loA = predictedA ? predicted_[a].lo : lo_[a];
      const Vec3& hiA = predictedA ? predicted_[a].hi : hi_[a];
      const Vec3& loB = predictedB ? predicted_[b].lo : lo_[b];
      const Vec3& hiB = predictedB ? predicted_[b].hi : hi_[b];
      ContactManifold m;
      if (!boundsWithin(loA, hiA, loB, hiB, margin) || !candidateManifold(world, k, margin, m)) {
        candidate.manifold = -1;
        continue;
      }
      if (candidate.manifold < 0) {
        candidate.manifold = static_cast<int>(manifolds_.size());
        manifolds_.push_back(m);
      } else {
        manifolds_[static_cast<std::size_t>(candidate.manifold)] = m;
      }
      place(world, a);
      place(world, b);
      if (contactOf(world, a, b, std::move(m), c)) fastContacts_.push_back(c);
    }
  // The pairs growCandidates added come after the sweep's: into the (a, b) order.
  if (!grownKeys_.empty())
    std::sort(fastContacts_.begin(), fastContacts_.end(),
              [](const ImpulseContact& x, const ImpulseContact& y) {
                return std::pair<int, int>(x.a, x.b) < std::pair<int, int>(y.a, y.b);
              });
  // DEVIATION(A.2 L6): every body goes back before COLLIDE, the fast ones too, with its
  // velocities recomputed exactly as they were: the slow pairs' prediction below and COLLIDE see
  // every body where it stands, and each fast contact keeps the lever arms it was found with
  // (the file comment, "Where COLLIDE acts"). A body that never went to its predicted pose
  // (nothing it touched) only gets the velocities putting it back would recompute.
  const auto putBack = [&](int i) {
    if (placed_[i]) {
      restorePose(world.bodies[i], saved_[i]);
      placed_[i] = 0;
    } else {
      world.bodies[i].updateVelocities();
    }
  };
  for (int j : partners_) putBack(j);
  for (int i : fast)
    if (moved_[i]) putBack(i);
  contacts_.clear();
  std::size_t f = 0;
  const auto keyOf = [](const ImpulseContact& contact) {
    return std::pair<int, int>(contact.a, contact.b);
  };
  for (std::size_t k = 0; k < pairs_.size(); ++k) {
    const PairReach& reachOf = pairReach_[k];
    const std::pair<int, int> key(reachOf.a, reachOf.b);
    for (; f < fastContacts_.size() && keyOf(fastContacts_[f]) < key; ++f)
      contacts_.push_back(fastContacts_[f]);
    if (skip_[key.first] || skip_[key.second]) continue;
    // A body that turned fast in this step: unless the two move together, its pairs are among
    // the fast ones now, and what they remember of the face comes after anything remembered
    // before.
    if ((moved_[key.first] || moved_[key.second]) && !predictedTogether(reachOf)) {
      pairs_[k].remembered = false;
      continue;
    }
    // Too far apart for any point to come within the margin: no contact, as predictedContact
    // would find, without reading the points.
    if (reachOf.count > 0 && !mayTouch(reachOf, margin)) continue;
    CachedPair& pair = pairs_[k];
    // No point to predict from: the narrow phase where the two slow bodies stand.
    if (pair.count == 0) {
      // Neither body moved since the first pass that looked: the narrow phase answers as then.
      if (pair.exact == kExactUnknown) {
        pair.exact = static_cast<int>(exactManifolds_.size());
        exactManifolds_.push_back(collideBoxes(Obb::of(world.bodies[key.first]),
                                               Obb::of(world.bodies[key.second]), margin));
        exactManifolds_.back().a = key.first;
        exactManifolds_.back().b = key.second;
      }
      const ContactManifold& m = exactManifolds_[static_cast<std::size_t>(pair.exact)];
      if (m.count > 0) {
        // Its face is remembered once while it stays slow, as the predicted pairs' below.
        contacts_.push_back(normals_.contactOf(world, m, !pair.remembered));
        pair.remembered = true;
      }
    } else if (predictedContact(world, pair, gravityStep, dt, margin, c)) {
      // The bodies have not moved since the cache was built: its manifold names the face, the
      // same in every pass, so remembering it once is remembering it every pass.
      if (!pair.remembered) normals_.remember(world, pair.manifold);
      pair.remembered = true;
      contacts_.push_back(c);
    }
  }
  contacts_.insert(contacts_.end(), fastContacts_.begin() + static_cast<std::ptrdiff_t>(f),
                   fastContacts_.end());
  return contacts_;
}

void ContactGathering::refreshIslands(const World& world) {
  const std::size_t n = world.bodies.size();
  if (islandSweep_ != sweeps_ || islands_.size() != n) {
    // A new sweep: the islands of its pairs and of the cached ones, every island active.
    std::vector<char> movable(n);
    for (std::size_t i = 0; i < n; ++i) movable[i] = static_cast<char>(!world.bodies[i].immovable);
    islands_.reset(movable);
    for (const PairReach& pair : pairReach_) islands_.join(pair.a, pair.b);
    joinedCandidates_ = 0;
    islandSweep_ = sweeps_;
  }
  for (; joinedCandidates_ < candidates_.size(); ++joinedCandidates_)
    islands_.join(candidates_[joinedCandidates_].a, candidates_[joinedCandidates_].b);
}

bool ContactGathering::candidateManifold(const World& world, std::size_t k, double margin,
                                         ContactManifold& manifold) {
  Candidate& candidate = candidates_[k];
  const Obb a = passBox(world, candidate.a);
  const Obb b = passBox(world, candidate.b);
  // Apart last time, and still apart along the same axis: the full test would say so too.
  ++passNarrowPhases_;
  if (candidate.apart && separatedBeyond(a, b, candidate.axis, margin)) return false;
  const SeparatingAxisResult sat = separatingAxisTest(a, b);
  manifold = buildContactManifold(a, b, sat, margin);
  candidate.axis = sat;
  candidate.apart = manifold.count == 0;
  return manifold.count > 0;
}

void ContactGathering::end(World&) {
  // A.2 L6, revertToOriginalPositions, already happened in begin(); the momenta the impulses
  // changed stay.
  moved_.clear();
  placed_.clear();
}

void ContactGathering::endStep() {
  normals_.endStep();
  cached_ = false;
  fast_.clear();
}

}  // namespace boxsim
