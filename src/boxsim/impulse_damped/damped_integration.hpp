/// \file
/// Damped integration, the thesis' real-time technique (\thesis{§5.2}, \alg{A.2}
/// DAMPEDINTEGRATION): Guendelman et al.'s collision and contact passes with the gravity trick,
/// then gravity, damping, fixing contact constraints and classifying geometric stability.
/// Around it, two of the basic techniques of \thesis{§4}: sleeping bodies at rest
/// (computational stability, \thesis{§4.5}) and random perturbation of high-speed collisions
/// (visual plausibility, \thesis{§4.2}). The method "damped".
#pragma once

#include <vector>

#include "boxsim/core/stepper.hpp"
#include "boxsim/geometric_stability/geometric_stability.hpp"
#include "boxsim/impulse_damped/contact_normal.hpp"
#include "boxsim/impulse_damped/dampen_objects.hpp"
#include "boxsim/impulse_damped/impulse_params.hpp"
#include "boxsim/impulse_damped/impulse_pass.hpp"
#include "boxsim/impulse_damped/visual_plausibility.hpp"

namespace boxsim {

/// Parameters of damped integration; each stage can be switched off for ablations.
struct DampedIntegrationParams {
  ImpulseParams impulse;          ///< collision and contact passes (\alg{A.2 L1-L2})
  DampingParams damping;          ///< DAMPENOBJECTS (\alg{A.2 L4})
  FixContactParams fixContacts;   ///< FIXCONTACTCONSTRAINTS (\alg{A.2 L5}); its slop also wakes
  GeometricStabilityParams geometricStability;  ///< SETGEOMETRICALLYSTABLE (\alg{A.2 L6})
  SleepParams sleep;              ///< sleeping bodies at rest (\thesis{§4.5}), on by default
  PlausibilityParams plausibility;  ///< perturbed fast collisions (\thesis{§4.2}), off by default
  bool damp = true;               ///< run DAMPENOBJECTS' momentum damping (L1-L21)
  bool fixContactConstraints = true;   ///< run FIXCONTACTCONSTRAINTS
  bool useGeometricStability = true;   ///< run SETGEOMETRICALLYSTABLE and COLLIDE L11-L14
};

/// DAMPEDINTEGRATION(Δt) of \alg{A.2} as a Stepper ("damped"), with sleeping and visual
/// plausibility.
///
/// **Sleeping** (\thesis{§4.5}; the rule is ours, the thesis states only the idea):
/// - *Falling asleep.* A movable body that has ended `round(timeToSleep / Δt)` consecutive
///   steps with momenta exactly zero (DAMPENOBJECTS zeroes small ones) and a pose bitwise
///   unchanged by the step falls asleep, provided every body supporting it (a contact whose
///   normal, pointing to it, has y above `supportNormalY`) is asleep or immovable. Bodies fall
///   asleep from the ground up, so a sleeping body's supports never move while it sleeps.
/// - *Asleep.* For the whole step a sleeping body stands in as immovable: zero inverse mass
///   and inertia, like the lower levels of shock propagation. It is not integrated, damped,
///   nudged by FIXCONTACTCONSTRAINTS (it is `held`) or classified; an awake body resting on it
///   is supported as by the ground. The broad phase drops pairs of two immovable bodies, so
///   two sleeping bodies, or a sleeping body and the ground, never reach the narrow phase; the
///   manifolds between them are remembered from the step they fell asleep, and shown to the
///   contact normal tracker every step so it keeps their closest faces (\thesis{§3.3.2}) for
///   when they wake. With no awake movable body at all the step does nothing.
/// - *Waking.* In every pass, just before COLLIDE, a contact between a sleeping body and an
///   awake one wakes the sleeper when the bodies approach faster than `wakeSpeed` g Δt, or when
///   the impulse COLLIDE would apply (with the sleeper immovable) would change the velocity of
///   the sleeper's contact point by more than `wakeImpulse` g Δt. The sleeper then gets its mass
///   back before that COLLIDE, so the hit moves it. At the end of a step a sleeping body that an
///   awake body penetrates deeper than the FIXCONTACTCONSTRAINTS slop wakes. At the start of a
///   step a sleeping body whose state was changed from outside (a kick, a move) wakes, and so
///   does one whose support is no longer asleep or immovable (a body that waited immovable
///   for its launch and has been launched).
/// - *Spreading.* A body that wakes wakes the sleeping bodies it supports, and they theirs:
///   their support may now move away. Nothing else spreads: sleeping bodies under or beside a
///   woken one stay asleep and hold it like the ground, until a contact of their own passes a
///   wake test. A hit spreads down a pile only as far as it is strong.
///
/// **Visual plausibility** (\thesis{§4.2}): in RESOLVECOLLISIONS (\alg{A.2 L1}) only, a
/// collision whose bodies approach faster than `plausibility.speedThreshold` has its normal
/// turned by a random rotation of at most `plausibility.maxAngleDeg` (VisualPlausibility).
class DampedIntegrationStepper final : public Stepper {
 public:
  /// A stepper with the given parameters; throws std::invalid_argument on iteration counts
  /// < 1, a time to sleep that is not a finite number > 0 s, negative or non-finite wake
  /// thresholds, a supportNormalY outside (0, 1), or invalid plausibility parameters.
  explicit DampedIntegrationStepper(const DampedIntegrationParams& params = {});
  std::string name() const override { return "damped"; }
  /// Every parameter, including "seed", the plausibility generator's seed.
  std::map<std::string, std::string> parameters() const override;
  /// \alg{A.2} DAMPEDINTEGRATION L1-L6 for one step of dt s, with sleeping bodies standing in
  /// as immovable and high-speed collisions perturbed as the class comment describes.
  /// StepStats::sleeping counts the bodies asleep after the step.
  StepStats step(World& world, double dt) override;
  /// The geometric stability of each body found at the end of the last step (\alg{A.2 L6}); a
  /// sleeping body keeps the flag it had when it fell asleep.
  const std::vector<char>& geometricallyStable() const { return stable_; }
  /// One flag per body of the world last stepped, 1 for a body asleep after the last step
  /// (\thesis{§4.5}). Bodies added to the world later start awake.
  const std::vector<char>& asleep() const { return asleep_; }
  /// The generator and counter of visual plausibility (\thesis{§4.2}).
  const VisualPlausibility& plausibility() const { return plausibility_; }

 private:
  /// What a sleeping body gives up while it stands in as immovable.
  struct MassProperties {
    double mass = 1.0;
    double invMass = 1.0;
    Vec3 IbodyInvDiag = Vec3::Ones();
  };

  void prepareSleep(World& world);
  void standIn(World& world, int body);
  void restore(World& world, int body);
  void restoreAll(World& world);
  void wake(World& world, int body);
  bool supportedBy(const ContactManifold& contact, int upper) const;
  double pointInverseMass(const World& world, int body, const Vec3& point, const Vec3& n) const;
  void beforeCollide(World& world, ImpulseContact& contact, const CollideCall& call,
                     bool collisionPass);
  void endSleep(World& world, const std::vector<ContactManifold>& contacts,
                const std::vector<BodyState>& start, double dt);

  DampedIntegrationParams params_;
  ContactNormalTracker normals_;
  VisualPlausibility plausibility_;
  std::vector<char> stable_;
  std::vector<char> asleep_;            // per body: asleep
  std::vector<char> standing_;          // per body: standing in as immovable in this step
  std::vector<int> stillSteps_;         // per body: consecutive steps exactly still
  std::vector<BodyState> sleepState_;   // per body: the state it fell asleep with
  std::vector<char> sleepStable_;       // per body: its geometric stability when it fell asleep
  std::vector<MassProperties> saved_;   // per body: mass properties while standing in
  // The contact manifolds at the end of the last step, in (a, b) order. Those of pairs that
  // both stand immovable are kept while they do: the broad phase skips such pairs, so the
  // narrow phase cannot report them again, and neither body has moved.
  std::vector<ContactManifold> resting_;
  std::vector<std::vector<int>> restingOf_;  // per body: indices into resting_
};

}  // namespace boxsim
