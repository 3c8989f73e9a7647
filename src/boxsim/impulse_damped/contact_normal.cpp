/// \file
/// Contact normal models (\thesis{§3.3.2}).
#include "boxsim/impulse_damped/contact_normal.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <stdexcept>

#include "boxsim/collision/contact_manifold.hpp"
#include "boxsim/collision/separating_axis.hpp"

namespace boxsim {

std::string contactNormalModelName(ContactNormalModel model) {
  return enumName(kContactNormalModelNames, model);
}

ContactNormalModel parseContactNormalModel(const std::string& name) {
  return parseEnum(kContactNormalModelNames, name, "contact normal model");
}

double boxSignedDistance(const Obb& box, const Vec3& p, Vec3* gradient) {
  const Vec3 local = box.axes.transpose() * (p - box.center);
  const Vec3 q = local.cwiseAbs() - box.halfExtents;
  const Vec3 sign(local.x() < 0.0 ? -1.0 : 1.0, local.y() < 0.0 ? -1.0 : 1.0,
                  local.z() < 0.0 ? -1.0 : 1.0);
  if ((q.array() <= 0.0).all()) {
    // Inside: the nearest face is the one whose slab the point is least deep in.
    int k = 0;
    for (int i = 1; i < 3; ++i)
      if (q[i] > q[k]) k = i;
    if (gradient) *gradient = sign[k] * box.axes.col(k);
    return q[k];
  }
  const Vec3 outside = q.cwiseMax(0.0);
  if (gradient) *gradient = box.axes * (outside.cwiseProduct(sign)).normalized();
  return outside.norm();
}

Vec3 ContactNormalTracker::signedDistanceNormal(const World& world,
                                                const ContactManifold& m) const {
  // Guendelman et al. test the vertices of each body against the other's signed distance; the
  // normal at a penetrating vertex is the distance's gradient. Boxes need no grid: the signed
  // distance is closed form. The depth-weighted mean of the corners' gradients is the normal.
  const Obb boxA = Obb::of(world.bodies[m.a]);
  const Obb boxB = Obb::of(world.bodies[m.b]);
  Vec3 sum = Vec3::Zero();
  for (int k = 0; k < 8; ++k) {
    Vec3 g;
    const double inB = boxSignedDistance(boxB, boxA.corner(k), &g);
    if (inB < 0.0) sum += -inB * (-g);  // B's outward normal points from b towards a
    const double inA = boxSignedDistance(boxA, boxB.corner(k), &g);
    if (inA < 0.0) sum += -inA * g;     // A's outward normal points from a towards b
  }
  // Edge-edge penetration puts no corner inside the other box: fall back to the manifold.
  if (sum.norm() < 1e-12) return m.normal;
  return sum.normalized();
}

ContactNormalTracker::FaceRef ContactNormalTracker::faceOf(const World& world,
                                                           const ContactManifold& m) {
  const bool onB = m.kind == AxisKind::FaceB;
  const Mat3& R = world.bodies[onB ? m.b : m.a].R;
  int axis = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(R.col(i).dot(m.normal)) > std::abs(R.col(axis).dot(m.normal))) axis = i;
  return FaceRef{onB, axis, R.col(axis).dot(m.normal) < 0.0 ? -1.0 : 1.0};
}

void ContactNormalTracker::remember(const World& world, const ContactManifold& m,
                                    FacePlaces* places) {
  if (model_ != ContactNormalModel::PreviousClosestFace || m.kind == AxisKind::EdgeEdge) return;
  if (!places) {
    current_.at(m.a, m.b) = faceOf(world, m);
    return;
  }
  placesInStep(m, *places);
  if (places->current < 0) places->current = static_cast<int>(current_.place(m.a, m.b));
  current_.value(static_cast<std::size_t>(places->current)) = faceOf(world, m);
}

ImpulseContact ContactNormalTracker::baseContact(const World& world, const ContactManifold& m) {
  // COLLIDE L7: findContactPoint, the centroid of the pair's manifold.
  const Vec3 p = m.centroid();
  const Friction friction = combinedFriction(world.bodies[m.a].friction, world.bodies[m.b].friction);
  ImpulseContact c{m.a,
                   m.b,
                   p,
                   m.normal,
                   m.depth,
                   Vec3(p - world.bodies[m.a].s.x),
                   Vec3(p - world.bodies[m.b].s.x),
                   friction,
                   {}};
  if (!friction.frictionless()) {
    // The points in order around the patch, as applyPatchFriction's couple limit walks them.
    const PatchOutline outline = patchOutline(m, p);
    for (; c.patch.count < m.count; ++c.patch.count) {
      const int i = outline.order[c.patch.count];
      c.patch.offsets[c.patch.count] = m.points[i].position - p;
      c.patch.pointOf[c.patch.count] = i;
    }
    c.patch.radius = contactPatchRadius(m, outline);
  }
  return c;
}

ImpulseContact ContactNormalTracker::contactOf(const World& world, const ContactManifold& m,
                                               bool record, FacePlaces* places) {
  ImpulseContact c = baseContact(world, m);
  switch (model_) {
    case ContactNormalModel::SeparatingAxis:
      break;
    case ContactNormalModel::SignedDistance:
      c.normal = signedDistanceNormal(world, m);
      break;
    case ContactNormalModel::PreviousClosestFace: {
      if (record) remember(world, m, places);
      // The pair's places, when kept, are found once in a step.
      if (places) placesInStep(m, *places);
      const FaceRef* previous =
          !places ? previous_.find(m.a, m.b)
          : places->previous >= 0 ? &previous_.value(static_cast<std::size_t>(places->previous))
                                  : nullptr;
      if (previous) c.normal = normalOf(world, m, *previous);
      break;
    }
  }
  return c;
}

std::vector<ImpulseContact> ContactNormalTracker::contactsOf(
    const World& world, const std::vector<ContactManifold>& manifolds) {
  std::vector<ImpulseContact> contacts;
  contacts.reserve(manifolds.size());
  for (const ContactManifold& m : manifolds) contacts.push_back(contactOf(world, m));
  return contacts;
}

void ContactNormalTracker::endStep() {
  previous_.swap(current_);
  current_.clear();
  generation_ = nextGeneration();
}

std::uint64_t ContactNormalTracker::nextGeneration() {
  static std::atomic<std::uint64_t> count{0};
  return ++count;
}

}  // namespace boxsim
