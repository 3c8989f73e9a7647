/// \file
/// \alg{DAMPENOBJECTS} (\thesis{§5.3}).
#include "boxsim/impulse_damped/dampen_objects.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "boxsim/impulse_damped/predicted_positions.hpp"

namespace boxsim {

namespace {
/// The axis of the box closest to ±y, as a signed world vector pointing up.
Vec3 upmostAxis(const RigidBody& body) {
  const int k = body.mostVerticalAxis();
  return body.R(1, k) < 0.0 ? Vec3(-body.R.col(k)) : Vec3(body.R.col(k));
}

/// Distance between two orientations as quaternions, blind to the sign ambiguity q ~ -q.
double quaternionDistance(const Quat& p, const Quat& q) {
  return std::min((p.coeffs() - q.coeffs()).norm(), (p.coeffs() + q.coeffs()).norm());
}
}  // namespace

bool isYAxisAligned(const RigidBody& body, double angleDeg) {
  return upmostAxis(body).y() >= std::cos(angleDeg * kPi / 180.0);
}

void tiltTowardsYAxis(RigidBody& body, double maxAngle) {
  const Vec3 up = upmostAxis(body);
  const Vec3 axis = up.cross(Vec3::UnitY());
  const double sine = axis.norm();
  if (sine < 1e-15) return;
  // The turn, min(θ, maxAngle) about axis / |axis|, θ the angle of up from y, as a quaternion
  // of its half angle. For θ itself from sin θ and cos θ by the half-angle formulas, so the
  // step needs only square roots: the C libraries' atan2, sin and cos differ in the last bit
  // now and then (docs/web.md), and the same scene must give the same bits everywhere.
  const double radius = std::sqrt(sine * sine + up.y() * up.y());
  const double cosine = up.y() / radius;
  double halfCos, halfSin;
  if (cosine >= std::cos(maxAngle)) {  // θ <= maxAngle: turn by θ, up onto y
    halfCos = std::sqrt(0.5 * (1.0 + cosine));
    halfSin = (sine / radius) / (2.0 * halfCos);
  } else {
    halfCos = std::cos(0.5 * maxAngle);
    halfSin = std::sin(0.5 * maxAngle);
  }
  const Vec3 v = (halfSin / sine) * axis;
  body.s.q = (Quat(halfCos, v.x(), v.y(), v.z()) * body.s.q).normalized();
  body.updateDerived();
}

void keepSupported(const World& world, const std::vector<ContactManifold>& contacts,
                   std::vector<char>& touched, ContactIslands& islands) {
  const int n = static_cast<int>(world.bodies.size());
  // Node n stands for every immovable body: they hold up whatever rests on them.
  islands.reset(static_cast<std::size_t>(n) + 1);
  const auto node = [&world, n](int i) {
    return world.bodies[static_cast<std::size_t>(i)].immovable ? n : i;
  };
  for (const ContactManifold& m : contacts) islands.join(node(m.a), node(m.b));
  // An immovable body's mark stays; damping leaves it alone anyway.
  for (int i = 0; i < n; ++i) {
    const std::size_t k = static_cast<std::size_t>(i);
    if (touched[k] && !world.bodies[k].immovable && !islands.together(i, n)) touched[k] = 0;
  }
}

void dampMomenta(World& world, double dt, const std::vector<char>& touched,
                 const DampingParams& params, DampingStats* stats,
                 const std::vector<SupportVerdict>& support) {
  const double u = world.gravity.norm() * dt;  // the velocity unit g Δt
  const double k1 = std::exp(-params.linearRate * dt);
  const double k2 = std::exp(-params.angularRate * dt);
  const double k3 = std::exp(-params.alignedAngularRate * dt);
  for (std::size_t i = 0; i < world.bodies.size(); ++i) {  // DAMPENOBJECTS L1
    RigidBody& o = world.bodies[i];
    // DAMPENOBJECTS L2: only bodies that had a contact interaction are damped.
    if (o.immovable || !touched[i]) continue;
    const double ell = o.halfExtents.minCoeff();
    const double pUnit = o.mass * u;                              // momentum of speed g Δt
    // Angular momentum of spin g Δt / ℓ about an axis of inertia (2/3) m ℓ² (a cube of half side ℓ).
    const double lUnit = (2.0 / 3.0) * o.mass * ell * u;
    const double rotationalBefore = o.s.L.dot(o.omega);
    // DAMPENOBJECTS L3-L5.
    // DEVIATION(DAMPENOBJECTS L3-L5, L9): the rates k1-k3 are the thesis' stand-in for friction
    // (§5.2, "friction slows things down"); a body with Coulomb friction has the real thing and
    // skips them, so that friction is not counted twice. The small-velocity tests below (L6-L21),
    // which bring bodies to rest, stay.
    const bool rates = o.friction.frictionless();
    // DEVIATION(DAMPENOBJECTS L6-L21): with the support test, the steps that bring a body to
    // rest act only on a body whose centre lies over its support (DampingParams::supportTest).
    const bool gated = params.supportTest && !support.empty();
    // DEVIATION(DAMPENOBJECTS L6-L21): a body that its Coulomb friction cannot hold is not
    // rested (markFrictionSlides).
    const bool slides = !support.empty() && support[i].slides;
    // DEVIATION(DAMPENOBJECTS L6-L21): nor one that it cannot hold with what rests on it
    // (SupportVerdict::held): a stack whose load lies beyond its lowest box's edge must tip, and
    // the rests, which see one box over its support at a time, stopped every box's first turn
    // (on a plank tilted 20° with μ = 0.5, five cubes crept 0.75 m in 4 s before they toppled,
    // four crawled 0.44 m in 8 s and never did).
    // A frictional body's hold stands in for the support test: `held` asks of the centre of its
    // whole load, the bodies pressing on it included, what `over` asks of its own centre. A box
    // of a pyramid pushed out over the edge of the row under it, held down by the rows it
    // carries, was held but not over, never rested, and kept trembling (0.1-0.2 mm a step for
    // 12 s), and with it the 19 boxes above it awake.
    const bool frictionalVerdict = !rates && !support.empty();
    const bool overSupport =
        !slides && (frictionalVerdict ? support[i].held : !gated || support[i].over);
    const bool yAxisAligned = isYAxisAligned(o, params.alignedAngleDeg) && overSupport;
    // DEVIATION(DAMPENOBJECTS L10): turning a box flat (towards y, about its centre) keeps it on
    // supporting faces that are level, but lifts it off a tilted one, or off all but the highest
    // of several whose tops are not level with each other (a pile): it then overhangs what is
    // left, tips back, and is turned flat again, for ever (measured in the clump on the ground:
    // cubes rocking in place at 0.1 m/s, one on a face tilted 0.5° creeping 1 mm/s).
    // On supports that are not level, a box is left as it lies.
    const bool turnFlat = !gated || support[i].level;
    if (rates) {
      o.s.P *= k1;
      o.s.L *= k2;
    }
    // DAMPENOBJECTS L6-L10: a box lying nearly flat is turned the last bit flat (L10); if it also
    // barely moves vertically it is resting on a face and loses its vertical velocity (L7-L9).
    // DEVIATION(DAMPENOBJECTS L7-L9): a body its Coulomb friction holds with its load over its
    // support (SupportVerdict::held) loses a small vertical velocity as an aligned one does,
    // though it lies tilted (on a slope, or on a tilted box of a heap). The passes leave each box
    // of a stack some of the g Δt of L3 (the restitution ramp of RESOLVECONTACTS L5 and the gravity
    // trick cannot settle a stack in one step), so it ends every step falling slowly; FIXCONTACT-
    // CONSTRAINTS lifts it back along the normal of a tilted support, which walks it down the
    // slope: three cubes stacked on a plank tilted 5° with μ = 0.5, which Coulomb holds, crept
    // 19 mm in 8 s and never slept, seven crept 0.28 m in 8 s with the top one reported falling at
    // 0.4 m/s. Now they stand and sleep after 0.5 s; five on a 20° plank, whose load lies beyond
    // the lowest box's downhill edge, are not held.
    // overSupport is SupportVerdict::held for a frictional body.
    // DEVIATION(DAMPENOBJECTS L7-L9): a held body whose supports reach the ground through held
    // bodies (SupportVerdict::grounded) cannot move down, and loses any downward velocity, not
    // only a small one (DampingParams::restGrounded says why).
    const bool held = overSupport && frictionalVerdict;
    const bool groundedFall =
        params.restGrounded && held && support[i].grounded && o.s.P.y() < 0.0;
    if (yAxisAligned || held) {
      if (std::abs(o.s.P.y()) < params.verticalVelocityEps * pUnit || groundedFall) {
        o.s.P.y() = 0.0;
        if (rates) o.s.L *= k3;
      }
      if (yAxisAligned && turnFlat) tiltTowardsYAxis(o, params.tiltRateDegPerS * kPi / 180.0 * dt);
    }
    // DAMPENOBJECTS L11-L19: component by component.
    // DEVIATION(DAMPENOBJECTS L14): the pseudocode tests ε5 twice, which would zero every component
    // the first test shrank; the second test uses its own, smaller ε6 (k5 then has an effect).
    // DEVIATION(DAMPENOBJECTS L11-L15): not the horizontal velocity of a body its support drags
    // (SupportVerdict::dragged; markFrictionSlides).
    const bool dragged = !support.empty() && support[i].dragged;
    for (int c = 0; c < 3 && overSupport; ++c) {
      if (!(dragged && c != 1)) {
        if (std::abs(o.s.P[c]) < params.linearSmallEps * pUnit) o.s.P[c] *= params.linearSmallFactor;
        if (std::abs(o.s.P[c]) < params.linearZeroEps * pUnit) o.s.P[c] = 0.0;
      }
      if (std::abs(o.s.L[c]) < params.angularSmallEps * lUnit) o.s.L[c] *= params.angularSmallFactor;
      if (std::abs(o.s.L[c]) < params.angularZeroEps * lUnit) o.s.L[c] = 0.0;
    }
    // DAMPENOBJECTS L20-L21: a small spin about y is stopped only when it is non-negative, as
    // written (spinZeroSymmetric: of either sign).
    if (overSupport && std::abs(o.s.L.y()) < params.spinZeroEps * lUnit &&
        (o.s.L.y() >= 0.0 || params.spinZeroSymmetric))
      o.s.L.y() = 0.0;
    o.updateVelocities();  // R is current: tiltTowardsYAxis updates it when it turns the body
    // DEVIATION(DAMPENOBJECTS L10, L16-L21): the rotational energy ½ Lᵀ R I⁻¹ Rᵀ L is not diagonal
    // in the world components of L, so scaling or zeroing one of them, or turning the box with L
    // held (tiltTowardsYAxis), can raise it. §5.3's rule is that damping never adds energy: where
    // these steps did, L is scaled back to the energy it had on entry.
    const double rotationalAfter = o.s.L.dot(o.omega);
    if (rotationalAfter > rotationalBefore) {
      o.s.L *= std::sqrt(rotationalBefore / rotationalAfter);
      o.updateVelocities();
    }
    if (stats) ++stats->damped;
  }
}

DampingStats dampenObjects(World& world, double dt, const std::vector<char>& touched,
                           const DampingParams& params, Integrator integrator,
                           const std::vector<SupportVerdict>& support, SavedPoses* before) {
  DampingStats stats;
  dampMomenta(world, dt, touched, params, &stats, support);
  // DAMPENOBJECTS L22: integrateObjectPositions(Δt, STANDARD_GRAVITY) with the velocities as they
  // now are. STANDARD_GRAVITY is read as gravity applied the usual way, which L3 already did to the
  // velocities; adding g Δt again, as the passes' VELOCITY_PLUS_GRAVITY does for a prediction,
  // would count the step's gravity twice in the positions.
  SavedPoses ownPoses;
  SavedPoses& old = before ? *before : ownPoses;
  integratePositions(world, dt, integrator, old);
  // DAMPENOBJECTS L23-L28: a body that would move less than ε10 and turn less than ε11 stays put.
  // DEVIATION(DAMPENOBJECTS L23): only bodies that had a contact interaction and lie with a face
  // perpendicular to gravity (§5.3's third mark of a chattering body) are snapped. A body in
  // free flight at the top of its arc moves little in one step too and must not hang there,
  // and a box just starting to tip off an edge moves little too: snapping it holds its pose,
  // the same contacts give it the same momenta, and it stays balanced on the edge for ever
  // (seen with 0.1 m cubes).
  const double step2 = world.gravity.norm() * dt * dt;  // the length unit g Δt²
  for (std::size_t i = 0; i < world.bodies.size(); ++i) {
    RigidBody& o = world.bodies[i];
    if (o.immovable || !touched[i] || !isYAxisAligned(o, params.alignedAngleDeg)) continue;
    // DEVIATION(DAMPENOBJECTS L23): with the support test, only over its support (as L6-L21).
    if (params.supportTest && !support.empty() && !support[i].over) continue;
    // DEVIATION(DAMPENOBJECTS L23): nor one its Coulomb friction cannot hold, alone or with what
    // rests on it, nor one its support drags (SupportVerdict::dragged).
    if (!support.empty() && (support[i].slides || support[i].dragged ||
                             (!o.friction.frictionless() && !support[i].held)))
      continue;
    // DEVIATION(DAMPENOBJECTS L26): the turn is measured by how far it carries the ends of the
    // body's longest axis (its largest half extent), not its thickness ℓ: a slab 1 m tall and
    // 0.1 m thick tipping at 1.4 rad/s turns by 0.011 in quaternion distance a step, within
    // ε11 g Δt² / ℓ, and was held upright, though its top moved 12 mm a step; and the body the
    // snap holds with friction loses its turn (restHeld). For a cube the two are the same length
    // (DampingParams::rotationSnapEps).
    const double reach = o.halfExtents.maxCoeff();
    const double deltaPosition = (o.s.x - old[i].x).norm();
    const double deltaRotation = quaternionDistance(o.s.q, old[i].q);
    if (deltaPosition < params.positionSnapEps * step2 &&
        deltaRotation < params.rotationSnapEps * step2 / reach) {
      // DEVIATION(DAMPENOBJECTS L26-L28): a body its friction holds (only frictional bodies
      // are ever held) and the rests left no linear momentum ends the step at rest
      // (DampingParams::restHeld); the velocities follow in restorePose.
      if (params.restHeld && !support.empty() && support[i].held && o.s.P.isZero(0.0))
        o.s.L.setZero();
      restorePose(o, old[i]);
      ++stats.snapped;
    }
  }
  return stats;
}

}  // namespace boxsim
