#include "boxsim/core/newtonian_impulse.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/Cholesky>

namespace boxsim {

double relativeNormalVelocity(const RigidBody& a, const RigidBody& b, const Vec3& ra,
                              const Vec3& rb, const Vec3& n) {
  return n.dot((b.v + b.omega.cross(rb)) - (a.v + a.omega.cross(ra)));
}

double relativeNormalVelocity(const RigidBody& a, const RigidBody& b, const Vec3& p,
                              const Vec3& n) {
  return relativeNormalVelocity(a, b, Vec3(p - a.s.x), Vec3(p - b.s.x), n);
}

double applyNewtonianImpulse(RigidBody& a, RigidBody& b, const Vec3& p, const Vec3& n,
                             double restitution) {
  return applyNewtonianImpulse(a, b, Vec3(p - a.s.x), Vec3(p - b.s.x), n, restitution);
}

void applyNormalImpulses(RigidBody& a, RigidBody& b, const Vec3& ra, const Vec3& rb, const Vec3& n,
                         double jA, double jB) {
  if (!a.immovable) {
    const Vec3 impulse = jA * n;
    a.s.P -= impulse;
    a.s.L -= ra.cross(impulse);
    a.updateVelocities();
  }
  if (!b.immovable) {
    const Vec3 impulse = jB * n;
    b.s.P += impulse;
    b.s.L += rb.cross(impulse);
    b.updateVelocities();
  }
}

namespace {

/// A.2's impulse magnitude j = -(1 + e) v⁻ / k at the contact (N s) into `j`, v⁻ (m/s) into
/// `vMinus`; false (no impulse) when the pair is not approaching or cannot be pushed (k <= 0).
bool newtonianMagnitude(const RigidBody& a, const RigidBody& b, const Vec3& ra, const Vec3& rb,
                        const Vec3& n, double restitution, double& vMinus, double& j) {
  vMinus = relativeNormalVelocity(a, b, ra, rb, n);
  if (vMinus >= 0.0) return false;
  const double denominator = pairInverseMass(a, b, ra, rb, n);
  if (denominator <= 0.0) return false;
  j = -(1.0 + restitution) * vMinus / denominator;
  return true;
}
}  // namespace

double applyNewtonianImpulse(RigidBody& a, RigidBody& b, const Vec3& ra, const Vec3& rb,
                             const Vec3& n, double restitution) {
  double vMinus = 0.0, j = 0.0;
  if (!newtonianMagnitude(a, b, ra, rb, n, restitution, vMinus, j)) return 0.0;
  applyNormalImpulses(a, b, ra, rb, n, j, j);
  return j;
}

double applyNewtonianImpulse(RigidBody& a, RigidBody& b, const Vec3& ra, const Vec3& rb,
                             const Vec3& n, double restitution, bool supportA, bool supportB) {
  if (!supportA && !supportB) return applyNewtonianImpulse(a, b, ra, rb, n, restitution);
  double vMinus = 0.0, j = 0.0;
  if (!newtonianMagnitude(a, b, ra, rb, n, restitution, vMinus, j)) return 0.0;
  // A body carried by a stable support lighter than itself: the support's inverse mass scaled by
  // the ratio of their masses, as if it were as heavy as the body it carries (the DEVIATION in
  // the header).
  const auto onLighterSupport = [&](const RigidBody& body, const Vec3& r, const RigidBody& support,
                                    const Vec3& rSupport) {
    if (body.immovable || !(support.invMass > body.invMass)) return j;
    const double k = body.invMass + rotationalInverseMass(body.Iinv, r, n);
    const double kSupport = support.invMass + rotationalInverseMass(support.Iinv, rSupport, n);
    return -(1.0 + restitution) * vMinus / (k + kSupport * (body.invMass / support.invMass));
  };
  const double jA = supportB ? onLighterSupport(a, ra, b, rb) : j;
  const double jB = supportA ? onLighterSupport(b, rb, a, ra) : j;
  applyNormalImpulses(a, b, ra, rb, n, jA, jB);
  return std::max(jA, jB);
}

namespace {
/// The largest s in [0, 1] with s p inside the convex polygon q (2D, its `count` >= 3 vertices
/// in order around a point inside it, the origin), or, for 2 vertices, the point of the
/// segment nearest to p along it (returned as the replacement of p).
Eigen::Vector2d pressureCentreWithin(const Eigen::Vector2d& p, const std::array<Eigen::Vector2d, 4>& q,
                                     int count) {
  if (count == 2) {
    const Eigen::Vector2d e = (q[1] - q[0]).normalized();
    const double lo = std::min(q[0].dot(e), q[1].dot(e)), hi = std::max(q[0].dot(e), q[1].dot(e));
    return std::clamp(p.dot(e), lo, hi) * e;
  }
  double scale = 1.0;
  for (int k = 0; k < count; ++k) {
    const Eigen::Vector2d& from = q[k];
    const Eigen::Vector2d& to = q[k + 1 < count ? k + 1 : 0];
    // The edge's normal, turned to point away from the origin inside.
    Eigen::Vector2d outward(to.y() - from.y(), from.x() - to.x());
    if (outward.dot(from) < 0.0) outward = -outward;
    const double reach = outward.dot(p), limit = outward.dot(from);
    if (reach > limit) scale = std::min(scale, limit / reach);
  }
  return scale * p;
}

using Vec5 = Eigen::Matrix<double, 5, 1>;
using Mat5 = FrictionRows::Mat5;

/// True when `rows` were built from exactly these inputs (bitwise), so they stand.
bool rowsCurrent(const FrictionRows& rows, const RigidBody& a, const RigidBody& b,
                 const Vec3& ra, const Vec3& rb, const Vec3& n, bool torsion, bool tipping) {
  return rows.valid && rows.torsion == torsion && rows.tipping == tipping &&
         sameBits(rows.ra, ra) && sameBits(rows.rb, rb) && sameBits(rows.n, n) &&
         sameBits(rows.IinvA, a.Iinv) && sameBits(rows.IinvB, b.Iinv) &&
         sameBits(rows.invMassA, a.invMass) && sameBits(rows.invMassB, b.invMass);
}

/// The inverse of a symmetric positive definite 5×5 matrix W (its lower triangle read) into
/// `inverse`, by the Cholesky factor C of W = C Cᵀ: C⁻¹ = M by forward substitution and
/// W⁻¹ = Mᵀ M. Loops of fixed length in a fixed order, so the same bits on every build; false,
/// and `inverse` unset, when W is not positive definite (a pivot not > 0, or not a number).
bool inverseOfPositiveDefinite(const FrictionRows::Mat5& W, FrictionRows::Mat5& inverse) {
  FrictionRows::Mat5 C = FrictionRows::Mat5::Zero();
  std::array<double, 5> reciprocal{};  // 1 / C(j, j)
  for (int j = 0; j < 5; ++j) {
    double pivot = W(j, j);
    for (int k = 0; k < j; ++k) pivot -= C(j, k) * C(j, k);
    if (!(pivot > 0.0)) return false;
    C(j, j) = std::sqrt(pivot);
    reciprocal[j] = 1.0 / C(j, j);
    for (int i = j + 1; i < 5; ++i) {
      double v = W(i, j);
      for (int k = 0; k < j; ++k) v -= C(i, k) * C(j, k);
      C(i, j) = v * reciprocal[j];
    }
  }
  FrictionRows::Mat5 M = FrictionRows::Mat5::Zero();  // C⁻¹, lower triangular
  for (int j = 0; j < 5; ++j) {
    M(j, j) = reciprocal[j];
    for (int i = j + 1; i < 5; ++i) {
      double v = 0.0;
      for (int k = j; k < i; ++k) v -= C(i, k) * M(k, j);
      M(i, j) = v * reciprocal[i];
    }
  }
  for (int i = 0; i < 5; ++i)
    for (int j = i; j < 5; ++j) {
      double v = 0.0;
      for (int k = j; k < 5; ++k) v += M(k, i) * M(k, j);
      inverse(i, j) = inverse(j, i) = v;
    }
  return true;
}

/// Builds the five friction rows of a contact (lever arms ra, rb in m, unit normal n from a to
/// b; the spin row when `torsion`, the tipping rows when `tipping`) and the pair's inverse mass
/// W in them and W⁻¹, into `rows` with the inputs they came from.
void buildRows(FrictionRows& rows, const RigidBody& a, const RigidBody& b, const Vec3& ra,
               const Vec3& rb, const Vec3& n, bool torsion, bool tipping) {
  rows.ra = ra;
  rows.rb = rb;
  rows.n = n;
  rows.IinvA = a.Iinv;
  rows.IinvB = b.Iinv;
  rows.invMassA = a.invMass;
  rows.invMassB = b.invMass;
  rows.torsion = torsion;
  rows.tipping = tipping;
  rows.valid = true;
  rows.t1 = n.unitOrthogonal();
  rows.t2 = n.cross(rows.t1);
  // The five rows friction works on, as velocity Jacobians: row i reads
  // L_i · (v_b - v_a) + G_b,i · ω_b - G_a,i · ω_a. Sliding along t1, t2 (L = t, G = r × t),
  // spin about n and tipping about t1, t2 (L = 0, G = n, t1, t2); a row left out is zero.
  rows.Ga.setZero();
  rows.Gb.setZero();
  rows.Ga.col(0) = ra.cross(rows.t1);
  rows.Ga.col(1) = ra.cross(rows.t2);
  rows.Gb.col(0) = rb.cross(rows.t1);
  rows.Gb.col(1) = rb.cross(rows.t2);
  if (torsion) rows.Ga.col(2) = rows.Gb.col(2) = n;
  if (tipping) {
    rows.Ga.col(3) = rows.Gb.col(3) = rows.t1;
    rows.Ga.col(4) = rows.Gb.col(4) = rows.t2;
  }
  // The pair's inverse mass in those rows:
  // W = (1/m_a + 1/m_b) LᵀL + G_aᵀ I_a⁻¹ G_a + G_bᵀ I_b⁻¹ G_b.
  Mat5& W = rows.W;
  W = rows.Ga.transpose() * (a.Iinv * rows.Ga) + rows.Gb.transpose() * (b.Iinv * rows.Gb);
  W(0, 0) += a.invMass + b.invMass;
  W(1, 1) += a.invMass + b.invMass;
  for (int i = 2; i < 5; ++i)
    if (rows.Ga.col(i).isZero(0.0)) W(i, i) = 1.0;  // a row left out: its impulse stays 0
  // W is symmetric positive definite (a pair's inverse mass restricted to independent rows).
  rows.factorised = inverseOfPositiveDefinite(W, rows.Winv);
  rows.normW = W.norm();
  rows.tippingFactorised = false;
  rows.slidingFactorised = false;
}

/// Coulomb's law on the sliding and spin rows of `total` (Goyal, Ruina and Papadopoulos'
/// ellipse): when (J_t, τ / ρ) exceeds μs N (N in N s, ρ = radius in m, no spin term without
/// torsion), scales them onto the ellipse of μd N; whether it did (the contact slides).
bool slideOntoEllipse(Vec5& total, const Friction& friction, double N, double radius,
                      bool torsion) {
  // The norm as written, not the C library's three-argument hypot, which libraries round
  // differently (docs/web.md); impulses are far from overflow.
  const double spin = torsion ? total(2) / radius : 0.0;
  const double load = std::sqrt(total(0) * total(0) + total(1) * total(1) + spin * spin);
  if (!(load > friction.muStatic * N)) return false;
  total.head<3>() *= load > 0.0 ? friction.muDynamic * N / load : 0.0;
  return true;
}

/// Coulomb: the sliding and spin rows of `total` limited (slideOntoEllipse), and when they
/// slide the couple set to the one that stops the tipping under the friction so limited, from
/// the sums `before` and the rows' velocities `slip` (m/s, rad/s) with inverse mass W = rows.W
/// (its tipping block is factorised into `rows` on first use).
void limitByCoulomb(Vec5& total, const Vec5& before, const Vec5& slip, FrictionRows& rows,
                    const Friction& friction, double N, double radius, bool torsion) {
  const Mat5& W = rows.W;
  if (slideOntoEllipse(total, friction, N, radius, torsion)) {
    // Sliding: the couple that stops the tipping under the friction as limited.
    const Eigen::Vector2d tip = slip.tail<2>() + W.block<2, 3>(3, 0) * (total.head<3>() - before.head<3>());
    if (!rows.tippingFactorised) {
      rows.tippingLlt.compute(W.block<2, 2>(3, 3));
      rows.tippingFactorised = true;
    }
    total.tail<2>() = before.tail<2>() - rows.tippingLlt.solve(tip);
  }
}

/// The sliding and spin rows of `total` (N s, N m s) that stop those rows under the couple of
/// `total` as it stands (rows 3, 4), from the sums `before` and the rows' velocities `slip`,
/// limited by Coulomb (slideOntoEllipse; N in N s, ρ = radius in m). W = rows.W; its sliding
/// block is factorised into `rows` on first use.
void stopSlidingUnderCouple(Vec5& total, const Vec5& before, const Vec5& slip, FrictionRows& rows,
                            const Friction& friction, double N, double radius, bool torsion) {
  const Mat5& W = rows.W;
  if (!rows.slidingFactorised) {
    rows.slidingLlt.compute(W.block<3, 3>(0, 0));
    rows.slidingFactorised = true;
  }
  if (rows.slidingLlt.info() != Eigen::Success) return;
  const Eigen::Vector3d slide =
      slip.head<3>() + W.block<3, 2>(0, 3) * (total.tail<2>() - before.tail<2>());
  total.head<3>() = before.head<3>() - rows.slidingLlt.solve(slide);
  slideOntoEllipse(total, friction, N, radius, torsion);
}

/// Holds the couple of `total` (its rows 3, 4, N m s about t1, t2) to a centre of pressure
/// p = n × couple / N within the patch polygon (N in N s).
void holdCoupleInPatch(Vec5& total, const ContactPatch& patch, const Vec3& t1, const Vec3& t2,
                       double N) {
  std::array<Eigen::Vector2d, 4> q;
  for (int k = 0; k < patch.count; ++k)
    q[k] = Eigen::Vector2d(patch.offsets[k].dot(t1), patch.offsets[k].dot(t2));
  // n × (x t1 + y t2) = x t2 - y t1, and back: couple = N p × n.
  const Eigen::Vector2d p = N > 0.0 ? Eigen::Vector2d(Eigen::Vector2d(-total(4), total(3)) / N)
                                    : Eigen::Vector2d(Eigen::Vector2d::Zero());
  const Eigen::Vector2d held = pressureCentreWithin(p, q, patch.count);
  total(3) = N * held.y();
  total(4) = -N * held.x();
}

/// Applies the change of the friction sums in the rows (N s, N m s): b receives +J and the
/// angular impulse Gb change, a the opposite, unless immovable.
void applyRowImpulse(RigidBody& a, RigidBody& b, const FrictionRows& rows, const Vec5& change) {
  const Vec3 J = change(0) * rows.t1 + change(1) * rows.t2;
  if (!a.immovable) {
    a.s.P -= J;
    a.s.L -= rows.Ga * change;
    a.updateVelocities();
  }
  if (!b.immovable) {
    b.s.P += J;
    b.s.L += rows.Gb * change;
    b.updateVelocities();
  }
}
}  // namespace

void applyPatchFriction(RigidBody& a, RigidBody& b, const Vec3& ra, const Vec3& rb, const Vec3& n,
                        const Friction& friction, const ContactPatch& patch, FrictionSum& sum) {
  if (a.immovable && b.immovable) return;
  // No budget and nothing applied yet: Coulomb allows no friction at all, and the sums stay 0.
  if (sum.normal == 0.0 && sum.torsional == 0.0 && sum.tangential.isZero(0.0) &&
      sum.couple.isZero(0.0))
    return;
  const bool torsion = patch.radius > 0.0;
  const bool tipping = patch.count >= 2;
  FrictionRows& rows = sum.rows;
  if (!rowsCurrent(rows, a, b, ra, rb, n, torsion, tipping))
    buildRows(rows, a, b, ra, rb, n, torsion, tipping);
  const Vec3& t1 = rows.t1;
  const Vec3& t2 = rows.t2;
  const Mat5& W = rows.W;
  const Vec3 dv = b.v - a.v;
  Vec5 slip = rows.Gb.transpose() * b.omega - rows.Ga.transpose() * a.omega;
  slip(0) += t1.dot(dv);
  slip(1) += t2.dot(dv);
  // Nothing slides, spins or tips: the sums stand (the budget only ever grows).
  if (slip.isZero(0.0)) return;
  Vec5 before;
  before << t1.dot(sum.tangential), t2.dot(sum.tangential), sum.torsional, t1.dot(sum.couple),
      t2.dot(sum.couple);
  // Sticking: the sums that stop every row.
  if (!rows.factorised) return;
  const Vec5 stop = rows.Winv * slip;
  Vec5 total = before - stop;
  if (!total.allFinite()) return;
  // Coulomb: (J_t, τ / ρ) within μs N, else on the ellipse of μd N.
  const double N = sum.normal;
  limitByCoulomb(total, before, slip, rows, friction, N, patch.radius, torsion);
  // The couple: its centre of pressure p = n × couple / N within the patch. Where the patch
  // holds back part of the couple that stops the tipping, the friction found with that couple
  // no longer stops the sliding, so it is found again under the couple held: a box tipping
  // over an edge had the couple that stops its turn, which also stops its contact's slide,
  // taken away whole (an edge holds no couple across it), and no friction was left at all.
  if (tipping) {
    const Eigen::Vector2d wanted = total.tail<2>();
    holdCoupleInPatch(total, patch, t1, t2, N);
    if (!sameBits(total(3), wanted.x()) || !sameBits(total(4), wanted.y()))
      stopSlidingUnderCouple(total, before, slip, rows, friction, N, patch.radius, torsion);
  }
  const Vec5 change = total - before;
  // The kinetic energy changes by Δ · slip + ½ Δᵀ W Δ: an increment that would raise it waits.
  if (change.dot(slip) + 0.5 * change.dot(W * change) > 1e-12 * slip.squaredNorm() / rows.normW) return;
  applyRowImpulse(a, b, rows, change);
  sum.tangential = total(0) * t1 + total(1) * t2;
  sum.torsional = total(2);
  sum.couple = total(3) * t1 + total(4) * t2;
}

}  // namespace boxsim
