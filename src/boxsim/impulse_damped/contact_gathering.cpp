/// \file
/// gatherCollisions at predicted positions (\alg{A.2}), every pass or once per step.
#include "boxsim/impulse_damped/contact_gathering.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/collision/contact_manifold.hpp"
#include "boxsim/collision/sweep_and_prune.hpp"

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

void movePredicted(RigidBody& body, double dt, const Vec3& extraVelocity) {
  body.s.x += dt * (body.v + extraVelocity);
  const Quat w(0.0, body.omega.x(), body.omega.y(), body.omega.z());
  body.s.q.coeffs() += (0.5 * dt) * (w * body.s.q).coeffs();
  body.s.q.normalize();
  body.updateDerived();
}

SavedPoses predictPositions(World& world, double dt, const Vec3& extraVelocity) {
  SavedPoses saved;
  saved.reserve(world.bodies.size());
  for (RigidBody& body : world.bodies) {
    saved.push_back({body.s.x, body.s.q, body.R, body.Iinv, body.immovable});
    if (!body.immovable) movePredicted(body, dt, extraVelocity);
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
  for (std::size_t i = 0; i < n; ++i) {
    const RigidBody& body = world.bodies[i];
    immovable_[i] = static_cast<char>(body.immovable);
    if (body.immovable) continue;
    widening[i] = params_.slowWidening * body.halfExtents.minCoeff();
    if (reach(body, gravityStep, dt) > params_.exactReach * body.halfExtents.minCoeff())
      fast_[i] = 1;
  }
  // One broad and narrow phase at the current poses, each body widened by more than a slow
  // body can move (slowWidening >= exactReach).
  pairs_.clear();
  for (const auto& [i, j] : sweepAndPrunePairs(world, margin, widening)) {
    if (fast_[i] || fast_[j]) continue;  // gathered as written, pass by pass
    const double pairMargin = margin + widening[i] + widening[j];
    ContactManifold m = collideBoxes(Obb::of(world.bodies[i]), Obb::of(world.bodies[j]), pairMargin);
    // Closer than the margin along every axis, yet no point: boxes passing corner by corner.
    // The pair stays, with no points, and gets the exact narrow phase every pass.
    if (m.depth <= -pairMargin) continue;
    m.a = i;
    m.b = j;
    const Vec3& xa = world.bodies[i].s.x;
    const Vec3& xb = world.bodies[j].s.x;
    // The normal model's choice now; its face is remembered only in the passes the pair touches.
    CachedPair pair{normals_.contactOf(world, m, false), m, {}, 0, false};
    for (int k = 0; k < m.count; ++k) {
      const ContactPoint& p = m.points[k];
      const Vec3 ra = p.position - xa, rb = p.position - xb;
      pair.points[pair.count++] = CachedPoint{p.position, p.depth,       ra,          rb,
                                              ra.cross(m.normal), rb.cross(m.normal),
                                              m.normal.dot(ra),   m.normal.dot(rb)};
    }
    pairs_.push_back(pair);
  }
  ++narrowPhases_;
  cacheMargin_ = margin;
  cached_ = true;
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
  double deepest = 0.0;
  for (int i = 0; i < pair.count; ++i) {
    const CachedPoint& p = pair.points[i];
    // n · (ω × r) = ω · (r × n).
    const double turning = a.omega.dot(p.raCrossN) - b.omega.dot(p.rbCrossN);
    const double centripetal = (nwa * a.omega.dot(p.ra) - wa2 * p.nDotRa) -
                               (nwb * b.omega.dot(p.rb) - wb2 * p.nDotRb);
    const double depth = p.depth + dt * (linear + turning) + (0.5 * dt * dt) * centripetal;
    if (depth <= -margin) continue;
    deepest = kept == 0 ? depth : std::max(deepest, depth);
    sum += p.position;
    ++kept;
  }
  if (kept == 0) return false;
  contact = pair.contact;
  contact.point = sum / static_cast<double>(kept);
  contact.depth = deepest;
  return true;
}

bool ContactGathering::exactContact(const World& world, int i, int j, double margin,
                                    ImpulseContact& contact) {
  ContactManifold m = collideBoxes(Obb::of(world.bodies[i]), Obb::of(world.bodies[j]), margin);
  if (m.count == 0) return false;
  m.a = i;
  m.b = j;
  contact = normals_.contactOf(world, m);
  return true;
}

std::vector<ImpulseContact>& ContactGathering::begin(World& world, double dt, GravityMode predict,
                                                     double margin) {
  const Vec3 gravityStep =
      predict == GravityMode::VelocityPlusGravity ? Vec3(dt * world.gravity) : Vec3(Vec3::Zero());
  if (params_.gathering == ContactGatheringMode::EveryPass) {
    // A.2 L2: integrateObjectPositions, remembering where every body was; L3: gatherCollisions.
    saved_ = predictPositions(world, dt, gravityStep);
    moved_.assign(world.bodies.size(), 1);
    contacts_ = normals_.contactsOf(world, findContacts(world, margin));
    return contacts_;
  }
  // DEVIATION(A.2 L2-L3): the prediction of the file comment.
  if (margin != cacheMargin_ || !cacheCovers(world)) buildCache(world, gravityStep, dt, margin);
  // A.2 L2 for the fast bodies only: they go to their predicted poses, as written. A body fast
  // when the cache was built stays fast for the step: the cache holds no pairs of its.
  const std::size_t n = world.bodies.size();
  moved_.assign(n, 0);
  saved_.resize(n);
  bool anyFast = false;
  for (std::size_t i = 0; i < n; ++i) {
    RigidBody& body = world.bodies[i];
    if (body.immovable) continue;
    if (!fast_[i] &&
        reach(body, gravityStep, dt) <= params_.exactReach * body.halfExtents.minCoeff())
      continue;
    saved_[i] = SavedPose{body.s.x, body.s.q, body.R, body.Iinv, false};
    moved_[i] = 1;
    anyFast = true;
    movePredicted(body, dt, gravityStep);
  }
  // A.2 L3 for the pairs with a fast body: the broad and narrow phase where the bodies now
  // stand, as written. Sorted by pair like the cache, so the two lists merge into one order.
  std::vector<std::pair<int, int>> fastPairs;
  if (anyFast)
    for (const std::pair<int, int>& p : sweepAndPrunePairs(world, margin))
      if (moved_[p.first] || moved_[p.second]) fastPairs.push_back(p);
  contacts_.clear();
  ImpulseContact c;
  std::size_t f = 0;
  for (CachedPair& pair : pairs_) {
    const std::pair<int, int> key(pair.contact.a, pair.contact.b);
    for (; f < fastPairs.size() && fastPairs[f] < key; ++f)
      if (exactContact(world, fastPairs[f].first, fastPairs[f].second, margin, c))
        contacts_.push_back(c);
    // No point to predict from: the narrow phase where the two slow bodies stand.
    // A body that turned fast in this step: its pairs are among the fast ones now, and what
    // they remember of the face comes after anything remembered before.
    if (moved_[key.first] || moved_[key.second]) {
      pair.remembered = false;
      continue;
    }
    if (pair.count == 0) {
      if (exactContact(world, key.first, key.second, margin, c)) contacts_.push_back(c);
    } else if (predictedContact(world, pair, gravityStep, dt, margin, c)) {
      // The bodies have not moved since the cache was built: its manifold names the face, the
      // same in every pass, so remembering it once is remembering it every pass.
      if (!pair.remembered) normals_.remember(world, pair.manifold);
      pair.remembered = true;
      contacts_.push_back(c);
    }
  }
  for (; f < fastPairs.size(); ++f)
    if (exactContact(world, fastPairs[f].first, fastPairs[f].second, margin, c))
      contacts_.push_back(c);
  return contacts_;
}

void ContactGathering::end(World& world) {
  // A.2 L6: revertToOriginalPositions; the momenta the impulses changed stay.
  for (std::size_t i = 0; i < moved_.size() && i < world.bodies.size(); ++i)
    if (moved_[i] && !world.bodies[i].immovable) restorePose(world.bodies[i], saved_[i]);
  moved_.clear();
}

void ContactGathering::endStep() {
  normals_.endStep();
  cached_ = false;
  fast_.clear();
}

}  // namespace boxsim
