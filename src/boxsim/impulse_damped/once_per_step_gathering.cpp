/// \file
/// The once-per-step gathering: gatherCollisions of Alg. A.2 found mostly once per step.
#include "boxsim/impulse_damped/once_per_step_gathering.hpp"

#include <algorithm>
#include <cstddef>
#include <utility>

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/collision/contact_manifold.hpp"
#include "boxsim/impulse_damped/parallel_for.hpp"
#include "boxsim/impulse_damped/predicted_positions.hpp"

namespace boxsim {

OncePerStepGathering::OncePerStepGathering(const ImpulseParams& params)
    : params_(params),
      candidates_(params.slowWidening),
      slowPairs_(params.pairReach, params.edgeCorners),
      kept_(params.keepNarrowPhases) {
  setParallelWork(nullptr);
}

void OncePerStepGathering::setParallelWork(ParallelWork* work) {
  work_ = work;
  // The kept narrow phases in batches when threads may share them or their work is measured;
  // on one thread, unmeasured, request after request (KeptNarrowPhase::setLoop).
  if (params_.threads > 1 || work)
    kept_.setLoop(keptNarrowPhaseLoop(params_.threads, params_.parallelNarrowPhases, work),
                  static_cast<std::size_t>(std::max(params_.parallelNarrowPhases, 0)));
  else
    kept_.setLoop({});
}

bool OncePerStepGathering::cacheCovers(const World& world, double margin) const {
  return margin == cacheMargin_ && cached_ && bodies_.sameMobility(world);
}

void OncePerStepGathering::beginStep(const World& world, const Vec3& gravityStep, double dt,
                                     double margin, ContactNormalTracker& normals) {
  if (!cacheCovers(world, margin)) buildCache(world, gravityStep, dt, margin, normals);
}

void OncePerStepGathering::buildCache(const World& world, const Vec3& gravityStep, double dt,
                                      double margin, ContactNormalTracker& normals) {
  const bool anchored = params_.predictedAnchor;
  bodies_.build(world, gravityStep, dt, params_.exactReach, anchored,
                touching_ && touching_->size() == world.bodies.size() ? touching_ : nullptr);
  slowPairs_.clear();
  // DEVIATION(RESOLVECOLLISIONS L2-L3, RESOLVECONTACTS L2-L3), with a predicted anchor: the slow
  // pairs are found where the first pass predicts their bodies (ImpulseParams::predictedAnchor).
  if (anchored) {
    anchorWorld_.bodies = world.bodies;
    anchorWorld_.gravity = world.gravity;
    anchorWorld_.restitution = world.restitution;
    anchorWorld_.groundIndex = world.groundIndex;
    for (std::size_t i = 0; i < anchorWorld_.bodies.size(); ++i)
      if (bodies_.anchorMoved[i]) movePredicted(anchorWorld_.bodies[i], dt, gravityStep);
  }
  const World& cacheWorld = cacheWorldOf(world);
  // Wider than the passes need: their own test (boundsWithin with `margin`) picks from the
  // candidates, so a wider sweep finds the same contacts, and it makes the candidates hold the
  // pairs FIXCONTACTCONSTRAINTS looks at after the passes (stepPairs), whose margin
  // (restingContactMargin) is wider by g Δt².
  candidates_.start(world, bodies_, slowPairs_.reaches(), gravityStep, dt,
                    margin + world.gravity.norm() * dt * dt, stamps_);
  // One narrow phase at the current poses for the slow pairs, each body widened by more than a
  // slow body can move (slowWidening >= exactReach): the pairs the broad phase gives with
  // margin and widening, picked from the candidates (whose growth is at least the widening) by
  // the sweep's own test.
  // The narrow phases in one batch (on several threads when ImpulseParams::threads > 1), the
  // pairs cached in candidate order.
  std::vector<StepCandidates::Candidate>& candidates = candidates_.candidates();
  std::vector<KeptNarrowPhase::Request>& batch = kept_.newBatch();
  batchCandidates_.clear();
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    StepCandidates::Candidate& candidate = candidates[k];
    candidate.cached = -1;
    candidate.exactEach = false;
    double pairMargin = 0.0;
    if (!slowPairs_.wanted(cacheWorld, bodies_, candidate.a, candidate.b, margin,
                           params_.slowWidening, pairMargin))
      continue;
    batch.push_back({candidate.a, candidate.b, pairMargin});
    batchCandidates_.push_back(static_cast<int>(k));
  }
  exactCandidates_.clear();
  kept_.collideAll(cacheWorld, [&](std::size_t r, const ContactManifold& m) {
    const KeptNarrowPhase::Request& request = batch[r];
    StepCandidates::Candidate& candidate =
        candidates[static_cast<std::size_t>(batchCandidates_[r])];
    // ImpulseParams::exactEdgePairs: an edge-edge manifold, or none within the margin although
    // the pair is within it, is not cached; the pair is gathered exactly in every pass.
    if (params_.exactEdgePairs &&
        (m.count > 0 ? m.kind == AxisKind::EdgeEdge : m.depth > -request.margin)) {
      candidate.exactEach = true;
      exactCandidates_.push_back(batchCandidates_[r]);
      return;
    }
    candidate.cached =
        slowPairs_.add(cacheWorld, bodies_, request.i, request.j, request.margin, m, normals);
  });
  exactSweep_ = candidates_.sweeps();
  ++narrowPhases_;
  // Every predicted pose and every candidate's answer is from before this build.
  buildStamp_ = stamps_.next();
  poses_.resize(world.bodies.size());
  manifolds_.clear();
  cacheMargin_ = margin;
  cached_ = true;
}

void OncePerStepGathering::gather(World& world, const Vec3& gravityStep, double dt, double margin,
                                  ContactNormalTracker& normals,
                                  std::vector<ImpulseContact>& contacts) {
  // DEVIATION(RESOLVECOLLISIONS L2-L3, RESOLVECONTACTS L2-L3): the prediction of the file comment.
  if (!cacheCovers(world, margin)) buildCache(world, gravityStep, dt, margin, normals);
  // The predicted poses kept are for one g Δt and Δt (a shock propagation pass, say, predicts
  // with another): for others they, and the answers found with them, are forgotten.
  if (!sameBits(gravityStep, predictedGravity_) || !sameBits(dt, predictedDt_)) {
    predictedGravity_ = gravityStep;
    predictedDt_ = dt;
    buildStamp_ = stamps_.next();
  }
  sortBodies(world, gravityStep, dt);
  gatherFastPairs(world, gravityStep, dt, margin, normals);
  putBackAll(world);
  mergeSlowPairs(world, dt, margin, normals, contacts);
}

void OncePerStepGathering::classify(const World& world, std::size_t i, const Vec3& gravityStep,
                                    double dt) {
  const RigidBody& body = world.bodies[i];
  // Reach and the swept-bounds test depend on v and ω alone (and on the swept bounds): with
  // both bitwise as in the last pass they are what they were then.
  PassMotion& motion = motion_[i];
  if (!(motion.stamp > buildStamp_ && sameBits(motion.v, body.v) &&
        sameBits(motion.omega, body.omega))) {
    motion.v = body.v;
    motion.omega = body.omega;
    motion.turn = dt * body.omega.norm() * bodies_.halfDiagonal[i];
    motion.reach = passReach(body.v, body.omega, gravityStep, dt, bodies_.halfDiagonal[i]);
    motion.sweptStamp = 0;
    motion.stamp = stamps_.next();
  }
  passReach_[i] = motion.reach;
  // With a predicted anchor a body is fast when this pass' prediction moved away from its
  // anchor by more than the slow bar: Δt (|v' - v'_0| + |ω - ω_0| ρ) (StepBodies::setPass).
  const double moved = bodies_.anchored
                           ? dt * bodies_.passVelocity[i].norm() + bodies_.passTurn[i]
                           : motion.reach;
  if (!bodies_.fast[i] && moved <= bodies_.slowReach[i]) return;
  fastThisPass_.push_back(static_cast<int>(i));
  const int index = static_cast<int>(i);
  if (motion.sweptStamp != candidates_.sweptStamp(index)) {
    const Vec3 u = body.v + gravityStep;
    motion.withinSwept =
        candidates_.withinSweptBounds(body, index, bodies_, Vec3(dt * u), motion.turn);
    motion.sweptStamp = candidates_.sweptStamp(index);
  }
  if (!motion.withinSwept) outgrown_.push_back(index);
}

void OncePerStepGathering::sortBodies(const World& world, const Vec3& gravityStep, double dt) {
  // A body fast when the cache was built stays fast for the step: the cache holds only its
  // pairs that moved together then, predicted while they still do.
  const std::size_t n = world.bodies.size();
  fastThisPass_.clear();
  outgrown_.clear();
  passReach_.assign(n, 0.0);
  motion_.resize(n);
  // The bodies of settled islands sit this pass out (contact_islands.hpp): they would stand,
  // move and touch as in the pass that settled them, and change nothing.
  refreshIslands(world);
  skip_.resize(n);
  anySkipped_ = false;
  for (std::size_t i = 0; i < n; ++i) {
    skip_[i] = static_cast<char>(islands_.settled(static_cast<int>(i)));
    anySkipped_ = anySkipped_ || skip_[i];
  }
  for (std::size_t i = 0; i < n; ++i) {
    bodies_.setPass(world.bodies[i], static_cast<int>(i), gravityStep, dt);
    if (!world.bodies[i].immovable && !skip_[i]) classify(world, i, gravityStep, dt);
  }
  // The step's candidates hold every pair that can come near while each body moves less than
  // its swept bounds allow; one that outgrew them needs its pairs found afresh, from the poses
  // the bodies stand at. A pair found so may join a settled island to an active one, which
  // takes it up again in this very pass.
  while (!outgrown_.empty()) {
    candidates_.grow(world, bodies_, slowPairs_.reaches(), gravityStep, dt, outgrown_, stamps_);
    outgrown_.clear();
    if (!anySkipped_) break;
    refreshIslands(world);
    anySkipped_ = false;
    for (std::size_t i = 0; i < n; ++i) {
      if (!skip_[i]) continue;
      if (islands_.settled(static_cast<int>(i))) {
        anySkipped_ = true;
      } else {
        skip_[i] = 0;
        classify(world, i, gravityStep, dt);
      }
    }
  }
  if (anySkipped_)
    for (std::size_t i = 0; i < n; ++i) skippedBodyPasses_ += skip_[i];
  islands_.flatten();
}

void OncePerStepGathering::refreshIslands(const World& world) {
  const std::size_t n = world.bodies.size();
  if (islandSweep_ != candidates_.sweeps() || islands_.size() != n) {
    // A new sweep: the islands of its pairs and of the cached ones, every island active.
    // A sleeper counts as movable: a contact may wake it within a pass (contact_islands.hpp).
    const bool sleepers = sleepers_ && sleepers_->size() == n;
    movable_.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      movable_[i] = static_cast<char>(!world.bodies[i].immovable || (sleepers && (*sleepers_)[i]));
    islands_.reset(movable_);
    for (const PairReach& pair : slowPairs_.reaches()) islands_.join(pair.a, pair.b);
    joinedCandidates_ = 0;
    islandSweep_ = candidates_.sweeps();
  }
  const std::vector<StepCandidates::Candidate>& candidates = candidates_.candidates();
  for (; joinedCandidates_ < candidates.size(); ++joinedCandidates_)
    islands_.join(candidates[joinedCandidates_].a, candidates[joinedCandidates_].b);
}

void OncePerStepGathering::gatherFastPairs(World& world, const Vec3& gravityStep, double dt,
                                           double margin, ContactNormalTracker& normals) {
  // RESOLVECOLLISIONS L2, RESOLVECONTACTS L2: the fast bodies only go to their predicted poses,
  // as written.
  poses_.startPass(world.bodies.size());
  bool anyFast = false;
  for (int i : fastThisPass_) {
    RigidBody& body = world.bodies[i];
    // A fast body with no candidate cannot touch anything in this pass: its predicted pose
    // would be looked at by no one, so it stays, with the velocities putting it back recomputes.
    if (!candidates_.hasCandidate(i)) {
      body.updateVelocities();
      continue;
    }
    // It stands at its predicted pose for the pass; the narrow phase looks at that pose where
    // it is kept (PassPoses::box), and the body goes there (moveToPredicted) only when one of
    // its pairs touches: then the normal model and COLLIDE see it there, as written. A body
    // that touches nothing ends the pass as if it had gone and come back (putBackAll).
    poses_.standFast(i);
    anyFast = true;
    poses_.prepare(body, i, dt, gravityStep, buildStamp_, stamps_);
  }
  // RESOLVECOLLISIONS L3, RESOLVECONTACTS L3: the pairs with a fast body, the broad and narrow phase where the bodies now
  // stand, as written. The broad phase is the broad phases' own test (boundsWithin) on the
  // candidates, so it keeps the pairs a sweep at these poses would find, in the same (a, b)
  // order, which is the cache's order too, so the two lists merge into one.
  fastContacts_.clear();
  fastTasks_.clear();
  fastTests_.clear();
  ContactManifold tested;  // one thread: the narrow phase of the pair being gathered
  // A sweep since the build (grow()) renumbered the candidates: the exactly gathered ones are
  // found again by their flag, which the sweep carried over.
  if (exactSweep_ != candidates_.sweeps()) {
    exactCandidates_.clear();
    const std::vector<StepCandidates::Candidate>& all = candidates_.candidates();
    for (std::size_t k = 0; k < all.size(); ++k)
      if (all[k].exactEach) exactCandidates_.push_back(static_cast<int>(k));
    exactSweep_ = candidates_.sweeps();
  }
  if (anyFast || !exactCandidates_.empty()) {
    const std::vector<StepCandidates::Candidate>& candidates = candidates_.candidates();
    // Only pairs with a fast body at its predicted pose (planFastPair's precondition): most
    // candidates of a settling heap have none and cost no call.
    // On one thread each pair is finished as soon as it is planned; on several, every pair is
    // planned first, so that the narrow phases can run together (testFastPairs). The same
    // operations in the same order for each pair, so the same bits. Planning first costs more
    // than it saves when too few narrow phases follow to be shared: on several threads a pass
    // plans first only when the last pass had enough (the count changes slowly from pass to
    // pass), or when the work is measured.
    const bool inOrder =
        !work_ && (params_.threads < 2 || lastPassTests_ < params_.parallelNarrowPhases);
    int tests = 0;
    FastPairTask task;
    const auto visit = [&](std::size_t k) {
      if (!planFastPair(world, k, gravityStep, dt, margin, task)) return;
      if (!inOrder) {
        if (task.test >= 0) {
          task.test = static_cast<int>(fastTests_.size());
          fastTests_.push_back(static_cast<int>(fastTasks_.size()));
        }
        fastTasks_.push_back(task);
        return;
      }
      if (task.test >= 0) {
        task.touching = candidateManifold(world, task, margin, tested);
        ++tests;
      }
      finishFastPair(world, task, tested, normals);
    };
    // The candidates with a fast body, in candidate order: from the fast bodies' own lists when
    // they hold few of the candidates (a few fast bodies among many slow ones), else by walking
    // every candidate. The same pairs in the same order either way.
    // The lists are made (once for the step's candidates) only when a body in eight or fewer
    // is fast.
    std::size_t listed = candidates.size();
    if (8 * fastThisPass_.size() <= world.bodies.size()) {
      candidates_.indexByBody(world.bodies.size());
      listed = 0;
      for (int i : fastThisPass_)
        if (poses_.fastAtPredicted(i)) listed += candidates_.ofBody(i).size();
    }
    if (4 * listed < candidates.size()) {
      fastCandidates_.clear();
      for (int i : fastThisPass_)
        if (poses_.fastAtPredicted(i)) {
          const std::span<const int> own = candidates_.ofBody(i);
          fastCandidates_.insert(fastCandidates_.end(), own.begin(), own.end());
        }
      fastCandidates_.insert(fastCandidates_.end(), exactCandidates_.begin(),
                             exactCandidates_.end());
      std::sort(fastCandidates_.begin(), fastCandidates_.end());
      fastCandidates_.erase(std::unique(fastCandidates_.begin(), fastCandidates_.end()),
                            fastCandidates_.end());
      for (int k : fastCandidates_) visit(static_cast<std::size_t>(k));
    } else {
      for (std::size_t k = 0; k < candidates.size(); ++k)
        if (poses_.fastAtPredicted(candidates[k].a) || poses_.fastAtPredicted(candidates[k].b) ||
            candidates[k].exactEach)
          visit(k);
    }
    lastPassTests_ = inOrder ? tests : static_cast<int>(fastTests_.size());
  }
  if (!fastTasks_.empty()) {
    testFastPairs(world, margin);
    for (const FastPairTask& task : fastTasks_)
      finishFastPair(world, task,
                     task.test >= 0 ? fastTested_[static_cast<std::size_t>(task.test)] : tested,
                     normals);
  }
  // The pairs grow() added come after the sweep's: into the (a, b) order.
  if (candidates_.grown())
    std::sort(fastContacts_.begin(), fastContacts_.end(),
              [](const ImpulseContact& x, const ImpulseContact& y) {
                return std::pair<int, int>(x.a, x.b) < std::pair<int, int>(y.a, y.b);
              });
}

// planFastPair, candidateManifold and finishFastPair run once for each candidate pair with a fast
// body in every pass, from gatherFastPairs' loop and testFastPairs': inlined there (GCC keeps
// them calls otherwise), the loop keeps its state in registers instead of passing it through
// every call. The same operations, the same bits.
[[gnu::always_inline]] inline
bool OncePerStepGathering::planFastPair(const World& world, std::size_t k,
                                        const Vec3& gravityStep, double dt, double margin,
                                        FastPairTask& task) {
  StepCandidates::Candidate& candidate = candidates_.candidates()[k];
  const int a = candidate.a, b = candidate.b;
  // Two bodies moving together: predicted with the cached pairs (mergeSlowPairs).
  if (candidate.cached >= 0 &&
      slowPairs_.predictedTogether(
          bodies_, slowPairs_.reaches()[static_cast<std::size_t>(candidate.cached)]))
    return false;
  // A pair of slow bodies gathered exactly (ImpulseParams::exactEdgePairs): both stand at
  // their predicted poses for its narrow phase, as a fast body's partner does; not in a pass
  // its island sits out.
  if (candidate.exactEach && !poses_.fastAtPredicted(a) && !poses_.fastAtPredicted(b)) {
    if (skip_[a] || skip_[b]) return false;
    for (const int j : {a, b}) {
      const RigidBody& body = world.bodies[j];
      if (body.immovable || poses_.atPredicted(j)) continue;
      poses_.standPartner(j);
      poses_.prepare(body, j, dt, gravityStep, buildStamp_, stamps_);
    }
  }
  // RESOLVECOLLISIONS L2, RESOLVECONTACTS L2: a moved body's slow partner too, as written, so the narrow phase sees both where
  // the pass predicts them. It moves by at most its reach, so if its bounds stay farther than
  // that plus the margin from the moved body's, the pair cannot touch in the pass and it need
  // not move for this pair (its current bounds then fail the test below as its predicted ones
  // would). It goes back before COLLIDE (putBackAll).
  if (poses_.fastAtPredicted(a) != poses_.fastAtPredicted(b)) {
    const int i = poses_.fastAtPredicted(a) ? a : b, j = poses_.fastAtPredicted(a) ? b : a;
    const RigidBody& body = world.bodies[j];
    if (!body.immovable && !poses_.partnerAtPredicted(j) &&
        boundsWithin(poses_.predicted(i).lo, poses_.predicted(i).hi, bodies_.lo[j], bodies_.hi[j],
                     margin + passReach_[j] + boundsRoundingSlack(body, bodies_.halfDiagonal[j]))) {
      poses_.standPartner(j);
      poses_.prepare(body, j, dt, gravityStep, buildStamp_, stamps_);
    }
  }
  // Both bodies where they stood when the pair was last looked at: the broad and narrow phase
  // would answer as then, so the answer is taken from then (the normal model still sees the
  // manifold, as it would).
  const std::uint64_t stampA = poses_.stamp(a, buildStamp_), stampB = poses_.stamp(b, buildStamp_);
  task = FastPairTask{};
  task.k = static_cast<int>(k);
  if (candidate.stampA == stampA && candidate.stampB == stampB) {
    task.manifold = candidate.manifold;
    return candidate.manifold >= 0;
  }
  candidate.stampA = stampA;
  candidate.stampB = stampB;
  // Bounds where each body stands in this pass: predicted once it moved, current before.
  const bool predictedA = poses_.atPredicted(a), predictedB = poses_.atPredicted(b);
  const Vec3& loA = predictedA ? poses_.predicted(a).lo : bodies_.lo[a];
  const Vec3& hiA = predictedA ? poses_.predicted(a).hi : bodies_.hi[a];
  const Vec3& loB = predictedB ? poses_.predicted(b).lo : bodies_.lo[b];
  const Vec3& hiB = predictedB ? poses_.predicted(b).hi : bodies_.hi[b];
  if (!boundsWithin(loA, hiA, loB, hiB, margin)) {
    candidate.manifold = -1;
    return false;
  }
  // Made only for the pairs whose bounds meet: most candidates of a flying clump stop above.
  // The narrow phase itself may wait for testFastPairs, and sees the same poses then: a slow
  // body whose bounds meet a fast one's stood as its partner above (the partner test is this
  // one widened), so no later pair makes either body stand elsewhere.
  task.test = 0;
  return true;
}

void OncePerStepGathering::testFastPairs(const World& world, double margin) {
  if (fastTested_.size() < fastTests_.size()) fastTested_.resize(fastTests_.size());
  const int tests = static_cast<int>(fastTests_.size());
  // Two pointers' worth of capture, which a std::function holds without allocating.
  const std::pair<const World*, double> pass{&world, margin};
  const auto test = [this, &pass](int t) {
    const std::size_t slot = static_cast<std::size_t>(t);
    FastPairTask& task = fastTasks_[static_cast<std::size_t>(fastTests_[slot])];
    task.touching = candidateManifold(*pass.first, task, pass.second, fastTested_[slot]);
  };
  // Each test reads the poses planFastPair left and writes its own candidate and slot: in any
  // order and on any thread, the same bits.
  if (sharedLoop(tests, params_.threads, params_.parallelNarrowPhases, work_,
                 &ParallelWork::testSeconds, &ParallelWork::testRounds, test))
    ++parallelTestPasses_;
}

[[gnu::always_inline]] inline
void OncePerStepGathering::finishFastPair(World& world, const FastPairTask& task,
                                          const ContactManifold& tested,
                                          ContactNormalTracker& normals) {
  StepCandidates::Candidate& candidate = candidates_.candidates()[static_cast<std::size_t>(task.k)];
  const int a = candidate.a, b = candidate.b;
  const auto addContact = [&](ContactManifold m) {
    poses_.moveToPredicted(world, a);
    poses_.moveToPredicted(world, b);
    if (m.count == 0) return;
    m.a = a;
    m.b = b;
    fastContacts_.push_back(normals.contactOf(world, m, true, &candidate.faces));
  };
  if (task.test < 0) {
    addContact(manifolds_[static_cast<std::size_t>(task.manifold)]);
    return;
  }
  if (task.axisChecked)
    ++passAxisChecks_;
  else
    ++passNarrowPhases_;
  if (!task.touching) {
    candidate.manifold = -1;
    return;
  }
  if (candidate.manifold < 0) {
    candidate.manifold = static_cast<int>(manifolds_.size());
    manifolds_.push_back(tested);
  } else {
    manifolds_[static_cast<std::size_t>(candidate.manifold)] = tested;
  }
  addContact(tested);
}

[[gnu::always_inline]] inline
bool OncePerStepGathering::candidateManifold(const World& world, FastPairTask& task,
                                             double margin, ContactManifold& manifold) {
  StepCandidates::Candidate& candidate = candidates_.candidates()[static_cast<std::size_t>(task.k)];
  const Obb a = poses_.box(world, candidate.a);
  const Obb b = poses_.box(world, candidate.b);
  // Apart last time, and still apart along the same axis: the full test would say so too.
  task.axisChecked = candidate.apart && separatedBeyond(a, b, candidate.axis, margin);
  if (task.axisChecked) return false;
  // Only the contact within the margin is wanted: a pair its faces prove apart beyond it is
  // settled without its edge axes (the same manifold, none).
  const SeparatingAxisResult sat = separatingAxisTestWithin(a, b, margin);
  manifold = buildContactManifold(a, b, sat, margin);
  candidate.axis = sat;
  candidate.apart = manifold.count == 0;
  return manifold.count > 0;
}

void OncePerStepGathering::putBackAll(World& world) {
  // DEVIATION(RESOLVECOLLISIONS L6, RESOLVECONTACTS L6): every body goes back before COLLIDE, the fast ones too, with its
  // velocities recomputed exactly as they were: the slow pairs' prediction and COLLIDE see
  // every body where it stands, and each fast contact keeps the lever arms it was found with
  // (contact_gathering.hpp, "Where COLLIDE acts"). A body that never went to its predicted
  // pose (nothing it touched) only gets the velocities putting it back would recompute.
  for (int j : poses_.partners()) poses_.putBack(world, j);
  for (int i : fastThisPass_)
    if (poses_.fastAtPredicted(i)) poses_.putBack(world, i);
}

void OncePerStepGathering::mergeSlowPairs(const World& world, double dt,
                                          double margin, ContactNormalTracker& normals,
                                          std::vector<ImpulseContact>& contacts) {
  // The contacts are written where they go, over the last pass' (the first `count` are this
  // pass'): a cached pair's contact is made in place, not made and then copied.
  std::size_t count = 0;
  const auto next = [&contacts, &count]() -> ImpulseContact& {
    if (count == contacts.size()) contacts.emplace_back();
    return contacts[count];
  };
  std::size_t f = 0;
  const auto keyOf = [](const ImpulseContact& contact) {
    return std::pair<int, int>(contact.a, contact.b);
  };
  const std::vector<PairReach>& reaches = slowPairs_.reaches();
  for (std::size_t k = 0; k < reaches.size(); ++k) {
    const PairReach& reach = reaches[k];
    const std::pair<int, int> key(reach.a, reach.b);
    for (; f < fastContacts_.size() && keyOf(fastContacts_[f]) < key; ++f, ++count)
      next() = fastContacts_[f];
    if (skip_[key.first] || skip_[key.second]) continue;
    // A body that turned fast in this step: unless the two move together, its pairs are among
    // the fast ones now.
    if ((poses_.fastAtPredicted(key.first) || poses_.fastAtPredicted(key.second)) &&
        !slowPairs_.predictedTogether(bodies_, reach)) {
      slowPairs_.forgetFace(k);
      continue;
    }
    if (slowPairs_.passContact(cacheWorldOf(world), bodies_, k, dt, margin, normals, kept_,
                               next()))
      ++count;
  }
  contacts.resize(count);
  contacts.insert(contacts.end(), fastContacts_.begin() + static_cast<std::ptrdiff_t>(f),
                  fastContacts_.end());
}

bool OncePerStepGathering::stepPairs(const World& world, double margin,
                                     std::vector<std::pair<int, int>>& pairs) const {
  if (!cached_ || !bodies_.sameMobility(world)) return false;
  return candidates_.pairsAt(world, margin, pairs);
}

}  // namespace boxsim
