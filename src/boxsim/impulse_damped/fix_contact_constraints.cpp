/// \file
/// FIXCONTACTCONSTRAINTS (\alg{A.2}, \thesis{§4.4}).
#include "boxsim/impulse_damped/fix_contact_constraints.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>

#include "boxsim/collision/broad_phase.hpp"
#include "boxsim/collision/separating_axis.hpp"
#include "boxsim/core/newtonian_impulse.hpp"

namespace boxsim {

double fixLiftLimit(const RigidBody& body, const FixContactParams& params, const Vec3& gravity,
                    double dt) {
  const double ell = body.halfExtents.minCoeff();
  const double travel = dt * (body.v.norm() + body.omega.norm() * body.halfExtents.norm()) +
                        gravity.norm() * dt * dt;
  return std::max(params.maxNudges * params.nudge * ell, travel);
}

namespace {
/// |n_y| at or below which a contact normal counts as level in FIXCONTACTCONSTRAINTS L3-L5
/// (unitless, 1e-6 rad of tilt): far above the rounding of a unit normal (~1e-16), far below
/// any slope a body could rest on.
constexpr double kLevelNormal = 1e-6;

/// How many nudges of `step` m the loop of FIXCONTACTCONSTRAINTS L6-L7 makes after a test
/// before the next test that could stop it: one, then more while the test before each is
/// certain to find the pair still deeper than `slop` (m), by the bound `after`
/// (DepthAfterTranslation::atLeast of k nudges, 1.01 k step for |offset| = 1 up to rounding);
/// at most `most` (>= 1). The bound falls as k grows (every operation in it is monotone), so the
/// first k it does not hold for is found by doubling and halving instead of one by one: a body
/// the step carried deep into a landing is nudged hundreds of times at once.
long nudgesBeforeTest(const DepthAfterTranslation& after, double step, double slop, long most) {
  const auto deeper = [&](long k) { return after.atLeast(1.01 * step * static_cast<double>(k)) > slop; };
  // Invariant: deeper(low) holds (or low = 0, before the first nudge), and the answer is above it.
  long low = 0, high = 1;
  while (high < most && deeper(high)) {
    low = high;
    high = std::min(most, 2 * high);
  }
  if (high >= most && deeper(most)) return most;
  // The answer is the first k in (low, high] where deeper(k) fails.
  while (high - low > 1) {
    const long mid = low + (high - low) / 2;
    if (deeper(mid))
      low = mid;
    else
      high = mid;
  }
  return high;
}
}  // namespace

int fixContactConstraints(World& world, double margin, const FixContactParams& params, double dt,
                          std::vector<ContactManifold>* gathered,
                          const std::vector<std::pair<int, int>>* pairs,
                          KeptNarrowPhase* kept, FixContactOrder* keptOrder) {
  // FIXCONTACTCONSTRAINTS L1: sortContactPointsAscending. Found straight into `gathered` when
  // the caller wants them.
  std::vector<ContactManifold> found;
  std::vector<ContactManifold>& contacts = gathered ? *gathered : found;
  if (pairs)
    findContacts(world, margin, *pairs, kept, contacts);
  else
    findContacts(world, margin, candidatePairs(world, margin), kept, contacts);
  // The order by height, as indices: the manifolds themselves stay in findContacts order for
  // `gathered`, and are not moved about by the sort.
  FixContactOrder ownOrder;
  FixContactOrder& order = keptOrder ? *keptOrder : ownOrder;
  order.resize(contacts.size());
  for (std::size_t k = 0; k < contacts.size(); ++k)
    order[k] = {contacts[k].centroid().y(), contacts[k].a, contacts[k].b, k};
  // The index makes every key distinct, so the plain sort gives the stable sort's order without
  // the stable sort's buffer.
  std::sort(order.begin(), order.end());
  int nudges = 0;
  for (const auto& entry : order) {  // FIXCONTACTCONSTRAINTS L2
    const ContactManifold& c = contacts[std::get<3>(entry)];
    // FIXCONTACTCONSTRAINTS L3-L5: the upper body moves, along the normal pointing from the lower
    // one to it. The upper body is the one the contact normal points up to, so that the
    // lower-to-upper normal points up; only a normal with no vertical part (within
    // kLevelNormal) leaves it to the centres' heights. Boxes of different sizes make the two
    // readings differ: a support whose centre is above that of a box resting on its slanted
    // face would, read by centres, be pushed down into what holds it.
    const double ny = c.normal.y();  // from a to b
    const bool aUpper = std::abs(ny) > kLevelNormal
                            ? ny < 0.0
                            : world.bodies[c.a].s.x.y() > world.bodies[c.b].s.x.y();
    const int upper = aUpper ? c.a : c.b;
    const int lower = aUpper ? c.b : c.a;
    RigidBody& moving = world.bodies[upper];
    if (moving.immovable) continue;
    RigidBody& other = world.bodies[lower];
    const Vec3 offset = aUpper ? Vec3(-c.normal) : Vec3(c.normal);
    const double ell = moving.halfExtents.minCoeff();
    // FixContactParams::sideShareAngleDeg: a side contact between two movable bodies moves
    // both apart, half a nudge each; the pair's relative motion per nudge is the same.
    const bool share = params.sideShareAngleDeg > 0.0 && !other.immovable &&
                       std::abs(c.normal.y()) < std::cos(params.sideShareAngleDeg * kPi / 180.0);
    // FIXCONTACTCONSTRAINTS L6-L7: nudge while they still intersect (beyond the documented slop).
    const double slop = params.slop * ell;
    const double step = params.nudge * ell;  // m, the length of one nudge (|offset| = 1)
    const auto limit =
        static_cast<long>(std::ceil(fixLiftLimit(moving, params, world.gravity, dt) / step));
    const Vec3 from = moving.s.x;  // where the contact was found
    long n = 0;
    while (n < limit) {
      const Obb box = Obb::of(moving);
      const Obb stable = Obb::of(other);
      // Only the depth is read below, and the test gives the swapped pair the same depth bit
      // for bit (separatingAxisTest): kept in the pair's own order (a, b), the test of the
      // contacts just found, or of this loop's last nudge, is handed back, not run again.
      const SeparatingAxisResult sat =
          !kept            ? separatingAxisTest(box, stable)
          : upper == c.a ? kept->axis(upper, box, lower, stable)
                         : kept->axis(lower, stable, upper, box);
      if (sat.depth <= slop) break;
      // One nudge, then more while the test before each is certain to find the pair still
      // deeper than the slop (DepthAfterTranslation, 1.01 for |offset| = 1 up to
      // rounding): those tests are left out, the nudges are the same additions, and the
      // loop stops where FIXCONTACTCONSTRAINTS L6-L7 would.
      const DepthAfterTranslation after(box, stable, sat);
      const long k = nudgesBeforeTest(after, step, slop, limit - n);
      // The nudges themselves, one addition each as L7 makes them (the same bits as nudging
      // and testing in turn); x alone: nothing derived changes.
      if (share) {
        const Vec3 half = (0.5 * step) * offset;
        for (long i = 0; i < k; ++i) moving.s.x += half;
        for (long i = 0; i < k; ++i) other.s.x -= half;
      } else {
        const Vec3 whole = step * offset;
        for (long i = 0; i < k; ++i) moving.s.x += whole;
      }
      nudges += static_cast<int>(k);
      n += k;
    }
    // FixContactParams::stopLiftedApproach (DEVIATION there): a frictional body lifted out of
    // more than stopLiftedOver times a step's fall from rest stops approaching the body it was
    // lifted from.
    if (params.stopLiftedApproach && !share &&
        static_cast<double>(n) * step > params.stopLiftedOver * world.gravity.norm() * dt * dt &&
        !combinedFriction(moving.friction, other.friction).frictionless()) {
      // The impulse of restitution 0 at the contact's centroid, the lower body held.
      const Vec3 point = c.centroid();
      RigidBody held = heldCopy(other);
      applyNewtonianImpulse(held, moving, Vec3(point - other.s.x), Vec3(point - from), offset, 0.0);
    }
  }
  return nudges;
}

}  // namespace boxsim
