/// \file
/// gatherCollisions at predicted positions (\alg{A.2}), every pass or once per step.
#include "boxsim/impulse_damped/contact_gathering.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/collision/contact_manifold.hpp"

namespace boxsim {

namespace {
/// n · (ω × (ω × r)), m/s²: the centripetal acceleration of a point turning with the body, along
/// n. Its Δt²/2 term keeps a tumbling box's corner on its arc instead of the arc's tangent,
/// which at 7 rad/s would wrongly dip a corner of a unit cube 6 mm into the ground.
double centripetal(const Vec3& omega, const Vec3& r, const Vec3& n) {
  return n.dot(omega) * omega.dot(r) - omega.squaredNorm() * n.dot(r);
}
}  // namespace

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
  if (!(params.wideningFactor >= 1.0) || !std::isfinite(params.wideningFactor) ||
      !(params.minWidening >= 0.0) || !std::isfinite(params.minWidening) ||
      !(params.exactReach >= 0.0) || !std::isfinite(params.exactReach))
    throw std::invalid_argument(
        "contact gathering: the widening factor must be a finite number >= 1, the least "
        "widening and the exact reach finite numbers >= 0 (units of l)");
}

double ContactGathering::reach(const RigidBody& body, const Vec3& gravityStep, double dt) const {
  if (body.immovable) return 0.0;
  return dt * ((body.v + gravityStep).norm() + body.omega.norm() * body.halfExtents.norm());
}

bool ContactGathering::cacheCovers(const World& world, const Vec3& gravityStep,
                                   double dt) const {
  if (!cached_ || widening_.size() != world.bodies.size()) return false;
  for (std::size_t i = 0; i < world.bodies.size(); ++i) {
    const RigidBody& body = world.bodies[i];
    if (static_cast<char>(body.immovable) != immovable_[i]) return false;
    if (reach(body, gravityStep, dt) > widening_[i]) return false;
  }
  return true;
}

void ContactGathering::buildCache(World& world, const Vec3& gravityStep, double dt,
                                  double margin) {
  const std::size_t n = world.bodies.size();
  widening_.assign(n, 0.0);
  immovable_.assign(n, 0);
  double widest = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const RigidBody& body = world.bodies[i];
    immovable_[i] = static_cast<char>(body.immovable);
    if (body.immovable) continue;
    // Headroom, so that the velocity changes of the coming passes rarely force a rebuild.
    widening_[i] = std::max(params_.wideningFactor * reach(body, gravityStep, dt),
                            params_.minWidening * body.halfExtents.minCoeff());
    widest = std::max(widest, widening_[i]);
  }
  // One narrow phase at the current poses; each pair gets the margin its own two bodies can
  // need, and the broad phase the widest any pair can.
  pairs_.clear();
  for (const auto& [i, j] : candidatePairs(world, margin + 2.0 * widest)) {
    const double pairMargin = margin + widening_[i] + widening_[j];
    ContactManifold m = collideBoxes(Obb::of(world.bodies[i]), Obb::of(world.bodies[j]), pairMargin);
    // Closer than the margin along every axis, yet no point: boxes passing corner by corner.
    // The pair stays, with no points, and gets the exact narrow phase every pass.
    if (m.depth <= -pairMargin) continue;
    m.a = i;
    m.b = j;
    const Vec3& xa = world.bodies[i].s.x;
    const Vec3& xb = world.bodies[j].s.x;
    CachedPair pair{normals_.contactOf(world, m), m.normal, {}, 0};
    for (int k = 0; k < m.count; ++k) {
      const ContactPoint& p = m.points[k];
      pair.points[pair.count++] = CachedPoint{p.position, p.depth, p.position - xa, p.position - xb};
    }
    pairs_.push_back(pair);
  }
  ++narrowPhases_;
  cacheMargin_ = margin;
  cached_ = true;
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
  if (margin != cacheMargin_ || !cacheCovers(world, gravityStep, dt))
    buildCache(world, gravityStep, dt, margin);
  // A.2 L2 for the fast bodies only: they go to their predicted poses, as written.
  const std::size_t n = world.bodies.size();
  moved_.assign(n, 0);
  saved_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    RigidBody& body = world.bodies[i];
    if (body.immovable ||
        reach(body, gravityStep, dt) <= params_.exactReach * body.halfExtents.minCoeff())
      continue;
    saved_[i] = SavedPose{body.s.x, body.s.q, body.R, body.Iinv, false};
    moved_[i] = 1;
    movePredicted(body, dt, gravityStep);
  }
  contacts_.clear();
  for (const CachedPair& pair : pairs_) {
    const RigidBody& a = world.bodies[pair.contact.a];
    const RigidBody& b = world.bodies[pair.contact.b];
    if (moved_[pair.contact.a] || moved_[pair.contact.b] || pair.count == 0) {
      // A fast body, or no point to predict from: the narrow phase of this pair where its
      // bodies stand for this pass (a fast body at its predicted pose), as written.
      ContactManifold m = collideBoxes(Obb::of(a), Obb::of(b), margin);
      if (m.count == 0) continue;
      m.a = pair.contact.a;
      m.b = pair.contact.b;
      contacts_.push_back(normals_.contactOf(world, m));
      continue;
    }
    const Vec3 ua = a.immovable ? a.v : Vec3(a.v + gravityStep);
    const Vec3 ub = b.immovable ? b.v : Vec3(b.v + gravityStep);
    const Vec3& nm = pair.manifoldNormal;
    const double linear = nm.dot(ua - ub);
    Vec3 sum = Vec3::Zero();
    int kept = 0;
    double deepest = 0.0;
    for (int i = 0; i < pair.count; ++i) {
      const CachedPoint& p = pair.points[i];
      const double depth = p.depth + dt * (linear + nm.dot(a.omega.cross(p.ra)) -
                                           nm.dot(b.omega.cross(p.rb))) +
                           (0.5 * dt * dt) * (centripetal(a.omega, p.ra, nm) -
                                              centripetal(b.omega, p.rb, nm));
      if (depth <= -margin) continue;
      deepest = kept == 0 ? depth : std::max(deepest, depth);
      sum += p.position;
      ++kept;
    }
    if (kept == 0) continue;
    ImpulseContact c = pair.contact;
    c.point = sum / static_cast<double>(kept);
    c.depth = deepest;
    contacts_.push_back(c);
  }
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
}

}  // namespace boxsim
