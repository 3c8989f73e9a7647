/// \file
/// The contact matrix A and vector b of Baraff 1994 for a world's point contacts.
#include "boxsim/analytic_lcp/contact_matrix.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace boxsim {

namespace {

/// The acceleration of the material point at p of a body with no contact force: gravity plus
/// ω̇ × r + ω × (ω × r), with ω̇ = I⁻¹ (L × ω) (Witkin and Baraff, rigid body dynamics §8).
Vec3 freePointAcceleration(const RigidBody& body, const Vec3& gravity, const Vec3& p) {
  const Vec3 r = p - body.s.x;
  const Vec3 omegaDot = body.Iinv * body.s.L.cross(body.omega);
  return gravity + omegaDot.cross(r) + body.omega.cross(body.omega.cross(r));
}

/// The part of A_ij that body k contributes, for contacts i and j both touching it with signs
/// si, sj (+1: the body is b of the contact, −1: a).
double sharedBodyTerm(const RigidBody& body, double si, const Vec3& pi, const Vec3& ni, double sj,
                      const Vec3& pj, const Vec3& nj) {
  const Vec3 ri = pi - body.s.x, rj = pj - body.s.x;
  return si * sj * (body.invMass * ni.dot(nj) + ri.cross(ni).dot(body.Iinv * rj.cross(nj)));
}

}  // namespace

Vec3 normalRate(const World& world, const ContactManifold& m) {
  const RigidBody& a = world.bodies[m.a];
  const RigidBody& b = world.bodies[m.b];
  if (m.kind == AxisKind::FaceA) return a.omega.cross(m.normal);
  if (m.kind == AxisKind::FaceB) return b.omega.cross(m.normal);
  // n = (e_a × e_b) / |e_a × e_b| with ė = ω × e; the edges are the separating axis'
  // indexA/indexB axes, which the manifold does not keep, so they are recovered as the box
  // axes most perpendicular to n.
  const auto edge = [&](const RigidBody& body) {
    int k = 0;
    for (int i = 1; i < 3; ++i)
      if (std::abs(body.R.col(i).dot(m.normal)) < std::abs(body.R.col(k).dot(m.normal))) k = i;
    return Vec3(body.R.col(k));
  };
  const Vec3 ea = edge(a), eb = edge(b);
  const Vec3 c = ea.cross(eb);
  const double length = c.norm();
  if (!(length > 1e-9)) return Vec3::Zero();
  const Vec3 cDot = a.omega.cross(ea).cross(eb) + ea.cross(b.omega.cross(eb));
  const Vec3 n = c / length;
  const Vec3 rate = (cDot - n * n.dot(cDot)) / length;
  return n.dot(m.normal) < 0.0 ? Vec3(-rate) : rate;
}

std::vector<PointContact> pointContacts(const World& world,
                                        const std::vector<ContactManifold>& manifolds) {
  std::vector<PointContact> contacts;
  for (const ContactManifold& m : manifolds) {
    const Vec3 rate = normalRate(world, m);
    for (int k = 0; k < m.count; ++k)
      contacts.push_back(PointContact{m.a, m.b, m.points[k].position, m.normal, rate});
  }
  return contacts;
}

void contactMatrix(const World& world, const std::vector<PointContact>& contacts, MatX& A,
                   VecX& b, const std::vector<char>& held) {
  // Immovable and held bodies neither move nor take forces: zero velocity and acceleration.
  const auto fixed = [&](int k) {
    return world.bodies[k].immovable || (!held.empty() && held[k]);
  };
  const auto velocityAt = [&](int k, const Vec3& p) {
    return fixed(k) ? Vec3(Vec3::Zero()) : world.bodies[k].pointVelocity(p);
  };
  const auto accelerationAt = [&](int k, const Vec3& p) {
    return fixed(k) ? Vec3(Vec3::Zero()) : freePointAcceleration(world.bodies[k], world.gravity, p);
  };
  const int n = static_cast<int>(contacts.size());
  const int bodies = static_cast<int>(world.bodies.size());
  for (int i = 0; i < n; ++i) {
    const PointContact& c = contacts[i];
    if (c.a < 0 || c.a >= bodies || c.b < 0 || c.b >= bodies || c.a == c.b)
      throw std::invalid_argument("contact matrix: contact " + std::to_string(i) +
                                  " names bodies " + std::to_string(c.a) + " and " +
                                  std::to_string(c.b) + " of " + std::to_string(bodies));
    if (!(std::abs(c.normal.norm() - 1.0) <= 1e-9))
      throw std::invalid_argument("contact matrix: contact " + std::to_string(i) +
                                  " has a normal that is not unit length");
  }
  A.setZero(n, n);
  b.resize(n);
  for (int i = 0; i < n; ++i) {
    const PointContact& ci = contacts[i];
    // b_i: a_i with every force zero.
    const Vec3 relativeAcceleration = accelerationAt(ci.b, ci.point) - accelerationAt(ci.a, ci.point);
    const Vec3 relativeVelocity = velocityAt(ci.b, ci.point) - velocityAt(ci.a, ci.point);
    b[i] = ci.normal.dot(relativeAcceleration) + 2.0 * ci.normalRate.dot(relativeVelocity);
    // A_ij over the bodies the two contacts share; symmetric, so j >= i and mirrored.
    for (int j = i; j < n; ++j) {
      const PointContact& cj = contacts[j];
      double sum = 0.0;
      for (const int k : {ci.a, ci.b}) {
        const double si = k == ci.b ? 1.0 : -1.0;
        for (const int l : {cj.a, cj.b})
          if (l == k && !fixed(k))
            sum += sharedBodyTerm(world.bodies[k], si, ci.point, ci.normal,
                                  l == cj.b ? 1.0 : -1.0, cj.point, cj.normal);
      }
      A(i, j) = A(j, i) = sum;
    }
  }
}

std::vector<Wrench> contactWrenches(const World& world, const std::vector<PointContact>& contacts,
                                    const VecX& f) {
  std::vector<Wrench> wrenches(world.bodies.size());
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const PointContact& c = contacts[i];
    const Vec3 F = f[static_cast<int>(i)] * c.normal;
    wrenches[c.b].force += F;
    wrenches[c.b].torque += (c.point - world.bodies[c.b].s.x).cross(F);
    wrenches[c.a].force -= F;
    wrenches[c.a].torque -= (c.point - world.bodies[c.a].s.x).cross(F);
  }
  return wrenches;
}

void bodyAccelerations(const World& world, const std::vector<PointContact>& contacts,
                       const VecX& f, std::vector<Vec3>& linear, std::vector<Vec3>& angular) {
  const std::size_t n = world.bodies.size();
  const std::vector<Wrench> wrenches = contactWrenches(world, contacts, f);
  linear.assign(n, Vec3::Zero());
  angular.assign(n, Vec3::Zero());
  for (std::size_t k = 0; k < n; ++k) {
    const RigidBody& body = world.bodies[k];
    if (body.immovable) continue;
    linear[k] = world.gravity + body.invMass * wrenches[k].force;
    angular[k] = body.Iinv * (wrenches[k].torque + body.s.L.cross(body.omega));
  }
}

}  // namespace boxsim
