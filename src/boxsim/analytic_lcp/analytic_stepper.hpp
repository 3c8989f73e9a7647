/// \file
/// The analytic method (\thesis{§2.6.1}, \thesis{§3.3.1}, \thesis{§4.3}): resting contact
/// forces from Baraff's LCP, collisions by chronologically ordered Newtonian impulses, those of
/// one collision's points applied at once (collision_impulses.hpp).
///
/// Every integration interval starts by gathering the contacts closer than the margin whose
/// points neither approach nor separate faster than `restingSpeed` (resting contacts,
/// Baraff 1994 §2), solving their LCP (lcp_solver.hpp) and holding the forces constant over
/// the interval. The loop of the basic colliding technique (advanceColliding) then integrates,
/// and bisects for the time of any collision, and applies impulses. A collision slower than
/// `stickySpeed` is perfectly inelastic (sticky collisions, \thesis{§4.3}): the two bodies
/// then rest on each other and the next interval's LCP holds them, instead of a cascade of ever
/// smaller bounces.
/// DEVIATION(\thesis{§4.3}, "purely elastic"): the thesis calls such a collision purely
/// elastic, but describes one that makes the bodies "stick together"; a purely elastic one
/// (restitution 1) would send them apart at full speed. Restitution 0, as here, is the
/// collision that sticks.
#pragma once

#include "boxsim/analytic_lcp/contact_matrix.hpp"
#include "boxsim/analytic_lcp/lcp_solver.hpp"
#include "boxsim/basic_colliding/basic_colliding.hpp"
#include "boxsim/geometric_stability/geometric_stability.hpp"
#include "boxsim/core/stepper.hpp"

namespace boxsim {

/// BasicCollidingParams with every default but the bisection's depth tolerance (m).
inline BasicCollidingParams withDepthTolerance(double depthTolerance) {
  BasicCollidingParams params;
  params.timeOfImpact.depthTolerance = depthTolerance;
  return params;
}

/// LcpParams with every default but epsilon, 1e-9 (m/s for the collision impulses' LCP).
inline LcpParams impulseLcpParams() {
  LcpParams params;
  params.epsilon = 1e-9;
  return params;
}

/// Parameters of the analytic method.
struct AnalyticParams {
  /// The collision loop: integrator (semi-implicit Euler by default, the deviation
  /// BasicCollidingParams explains), bisection tolerances, event and impulse bounds. Its depth
  /// tolerance is 1e-4 m (a tenth of a millimetre) rather than the basic technique's 1e-9 m:
  /// resting contacts held by LCP forces drift into each other by rounding, by the ε the solver
  /// lets pass (½ ε t², 1e-9 m within 15 ms at ε = 1e-5 m/s²) and by the drift correction's
  /// own overshoot, and each such overlap would otherwise be a collision and a bisection.
  BasicCollidingParams loop = withDepthTolerance(1e-4);
  /// Baraff's solver with the thesis' ε and force clamp.
  LcpParams lcp;
  /// The same solver for the impulses of a collision at all its points at once
  /// (collision_impulses.hpp); its epsilon is in m/s: 1e-9 m/s, a millionth of the slowest
  /// collision (restingSpeed) and far above the rounding of A j (~1e-15 m/s at a few m/s).
  LcpParams collisionLcp = impulseLcpParams();
  /// m: pairs closer than this take part in the contact LCP (as BasicCollidingParams'
  /// contactMargin counts contacts). 1e-3 m.
  double contactMargin = 1e-3;
  /// m/s: a contact point whose normal relative velocity is within ± this is resting and gets
  /// an LCP force; faster ones are collisions (approaching) or separating. 1e-2 m/s: the speed
  /// one 60 Hz step of gravity cannot build from rest in a tenth of a step, well above the
  /// rounding of a resting stack, below any visible bounce.
  double restingSpeed = 1e-2;
  /// Contact points of face contacts: every vertex of the contact area (up to 8, \thesis{§3.2};
  /// contactArea in collision/contact_manifold.hpp) when true, the manifold's at most 4 when
  /// false. The forces differ, the accelerations do not.
  bool fullContactArea = true;
  /// Drift correction of resting contacts, on by default:
  /// DEVIATION(\thesis{§3.3.1}, Baraff 1994 §2): the LCP asks each resting contact for
  /// a_i >= −v_i / Δt − β d_i / Δt² instead of a_i >= 0. Here v_i is the contact's normal
  /// relative velocity (negative: approaching) and d_i its penetration depth (m, positive when
  /// overlapping). A resting contact that rounding, ε or the integrator has left approaching or
  /// overlapping is then stopped and pushed out within a step or a few, instead of drifting on
  /// until the collision loop must bisect for it again. Without it, a tower of 10 drifts 5 µm
  /// in 5 s and hits the event limit in 40 % of its steps (measured). Off gives Baraff's LCP
  /// as the thesis used it.
  bool driftCorrection = true;
  /// β of the drift correction: the share of a resting contact's penetration removed per step.
  /// 0.2, a common choice that removes it within a few steps without making the box jump.
  double driftBeta = 0.2;
  /// The geometric-stability exclusion (\thesis{§5.4}), off by default so that the method is
  /// Baraff's LCP as \thesis{§3.3.1} uses it; \thesis{§5.4} pairs it with analytic contact
  /// forces for Fig. 5.6, and the analytic chapter's figure of it turns it on (what it saves
  /// is the LCP's size). Stable bodies (geometric_stability.hpp) cannot be accelerated
  /// by gravity or by frictionless contact forces: their contacts with one another leave the
  /// LCP, they stand in it as immovable where unstable bodies touch them, and they are held
  /// against gravity. Every body's acceleration is the full LCP's (tested); the system shrinks.
  bool useGeometricStability = false;
  /// Tolerances of the stability classifier.
  GeometricStabilityParams geometricStability;
  /// Sticky collisions (\thesis{§4.3}) on or off.
  bool sticky = true;
  /// m/s: collisions approaching slower than this are perfectly inelastic when sticky is on.
  /// 0.5 m/s, the impact speed of a 1.3 cm drop: slow enough that a bounce would be barely
  /// visible, fast enough to catch the cascade of small bounces that ends a fall.
  double stickySpeed = 0.5;
};

/// The analytic method as a Stepper ("analytic").
class AnalyticStepper final : public Stepper {
 public:
  /// A stepper with the given parameters; throws std::invalid_argument on out-of-range ones.
  explicit AnalyticStepper(const AnalyticParams& params = {});
  std::string name() const override { return "analytic"; }
  std::map<std::string, std::string> parameters() const override;
  std::string workLimit() const override { return collisionLoopWorkLimit(params_.loop); }
  /// One step of dt s: advanceColliding with the LCP contact forces and sticky collisions.
  StepStats step(World& world, double dt) override;
  /// The wrench on each body of the LCP contact forces at the world's current state (the
  /// extraForces hook) for an interval of dt s (the drift correction needs it): one per body,
  /// zero for bodies with no resting contact.
  std::vector<Wrench> contactWrenches(const World& world, double dt) const;
  /// The accelerations those wrenches and gravity give: for body k, element 2k is its linear
  /// acceleration (m/s²) and 2k + 1 its angular acceleration ω̇ = I⁻¹(τ + L × ω) (rad/s²); zeros
  /// for immovable bodies. Zero for every body of a set held at rest (what the stability tests
  /// compare with).
  std::vector<Vec3> contactAccelerations(const World& world, double dt) const;
  /// Contacts in the last LCP solved by contactWrenches (after any exclusion), for benches.
  int lastLcpSize() const { return lastLcpSize_; }
  /// The size contactWrenches' LCP would have at the world's current state (resting contact
  /// points after any exclusion), without solving it: for scenes whose full LCP is too large to
  /// time.
  int lcpSize(const World& world) const { return static_cast<int>(restingSystem(world).contacts.size()); }
  /// N, LcpResult::mostNegativeForce of the last LCP solved: what the force clamp removed (or,
  /// with it off, left in), for the figure of the failure \thesis{§3.3.1} reports.
  double lastMostNegativeForce() const { return lastMostNegativeForce_; }

 private:
  /// The resting contacts the LCP is built from, with the stability flags behind the exclusion.
  struct RestingSystem {
    std::vector<char> stable;  ///< empty without the exclusion
    std::vector<PointContact> contacts;
    std::vector<double> approach;  ///< m/s, normal relative velocity of each contact
    std::vector<double> depth;     ///< m, penetration of each contact
  };
  RestingSystem restingSystem(const World& world) const;

  AnalyticParams params_;
  mutable int lastLcpSize_ = 0;
  mutable double lastMostNegativeForce_ = 0.0;
};

}  // namespace boxsim
