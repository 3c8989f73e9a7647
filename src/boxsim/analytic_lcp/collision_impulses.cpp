/// \file
/// Simultaneous collision impulses at every point of a colliding pair (Baraff 1989, §8).
#include "boxsim/analytic_lcp/collision_impulses.hpp"

#include <algorithm>

#include "boxsim/analytic_lcp/contact_matrix.hpp"
#include "boxsim/core/newtonian_impulse.hpp"

namespace boxsim {

int applySimultaneousImpulses(World& world, const PairCollision& collision,
                              const LcpParams& params) {
  const RigidBody& a = world.bodies[collision.a];
  const RigidBody& b = world.bodies[collision.b];
  const int n = static_cast<int>(collision.points.size());
  std::vector<PointContact> contacts;
  VecX bias(n);
  bool approaching = false;
  for (int i = 0; i < n; ++i) {
    const Vec3& p = collision.points[i];
    contacts.push_back(PointContact{collision.a, collision.b, p, collision.normal, Vec3::Zero()});
    const double vMinus = relativeNormalVelocity(a, b, p, collision.normal);
    approaching = approaching || vMinus < -params.epsilon;
    bias[i] = vMinus + collision.restitution[i] * std::min(vMinus, 0.0);
  }
  if (!approaching) return 0;
  // A of the forces is A of the impulses: both map a magnitude at point j to the change it
  // makes at point i (acceleration per N, velocity per N s). Its b, the accelerations with no
  // force, is not needed here.
  MatX A;
  VecX unused;
  contactMatrix(world, contacts, A, unused);
  const LcpResult lcp = solveContactLcp(A, bias, params);
  // The impulses j_i n at the points: +j_i n on b, -j_i n on a, both at p_i.
  Vec3 impulse = Vec3::Zero(), momentA = Vec3::Zero(), momentB = Vec3::Zero();
  for (int i = 0; i < n; ++i) {
    const Vec3 J = lcp.f[i] * collision.normal;
    impulse += J;
    momentA += (collision.points[i] - a.s.x).cross(J);
    momentB += (collision.points[i] - b.s.x).cross(J);
  }
  for (const int k : {collision.a, collision.b}) {
    RigidBody& body = world.bodies[k];
    if (body.immovable) continue;
    const double sign = k == collision.b ? 1.0 : -1.0;
    body.s.P += sign * impulse;
    body.s.L += sign * (k == collision.b ? momentB : momentA);
    body.updateVelocities();
  }
  return static_cast<int>((lcp.f.array() > 0.0).count());
}

}  // namespace boxsim
