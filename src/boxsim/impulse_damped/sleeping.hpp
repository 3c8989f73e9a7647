/// \file
/// Computational stability (\thesis{§4.5}): bodies that have come to rest sleep, stand in as
/// immovable, cost nothing, and wake when something disturbs them. The thesis names the idea and
/// gives no rule; the rule here is ours (Sleeping states it). DampedIntegrationStepper calls it
/// around the passes of \alg{A.2}.
#pragma once

#include <vector>

#include "boxsim/collision/contact.hpp"
#include "boxsim/core/world.hpp"
#include "boxsim/impulse_damped/chatter_history.hpp"
#include "boxsim/impulse_damped/contact_normal.hpp"
#include "boxsim/impulse_damped/impulse_params.hpp"
#include "boxsim/impulse_damped/impulse_pass.hpp"

namespace boxsim {

/// Sleeping bodies at rest (\thesis{§4.5}; the rule is ours, the thesis states only the idea),
/// as damped integration (\alg{A.2}) runs it. It owns the per-body sleep state between steps.
///
/// - *Falling asleep.* A movable body that has ended `round(timeToSleep / Δt)` consecutive
///   steps with a pose bitwise unchanged by the step (DAMPENOBJECTS' snap holds a resting
///   body's pose; with SleepParams::stillByPose off, momenta exactly zero as well) falls
///   asleep, its momenta zeroed, provided every body supporting it (a contact whose
///   normal, pointing to it, has y above `supportNormalY`) is asleep or immovable. Bodies fall
///   asleep from the ground up, so a sleeping body's supports never move while it sleeps.
///   With SleepParams::chatterDetection on, a body that chatters over the same time
///   (ChatterHistory: its pose within an envelope, no energy gained, from gravity or
///   otherwise) and that something supports counts as still, and its momenta are zeroed as it
///   falls asleep.
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
/// A step calls, in this order: a RestoreOnExit guard, begin(), beforeCollide() in each pass,
/// holdStability() after SETGEOMETRICALLYSTABLE, skippedContacts() for the normal tracker, and
/// end(). Between steps no body stands in, so the world keeps every body's own mass.
/// With SleepParams::enabled false every body stays awake and the step is \alg{A.2} as written.
class Sleeping {
 public:
  /// Sleeping with the given parameters; `slop` is FIXCONTACTCONSTRAINTS' slop in units of ℓ
  /// (FixContactParams::slop), the penetration beyond which a sleeping body wakes. Throws
  /// std::invalid_argument on a time to sleep that is not a finite number > 0 s, negative or
  /// non-finite wake thresholds, or a supportNormalY outside (0, 1).
  explicit Sleeping(const SleepParams& params = {}, double slop = FixContactParams{}.slop);

  /// Gives every stand-in its own mass properties back when it goes out of scope, normally or
  /// by an exception, so the world never keeps a sleeping body's borrowed infinite mass
  /// between steps. Make it before begin(), which turns sleeping bodies into stand-ins.
  class RestoreOnExit {
   public:
    /// A guard for the stand-ins of `sleeping` in `world`; both must outlive it.
    RestoreOnExit(Sleeping& sleeping, World& world) : sleeping_(sleeping), world_(world) {}
    RestoreOnExit(const RestoreOnExit&) = delete;             ///< one guard, one restore
    RestoreOnExit& operator=(const RestoreOnExit&) = delete;  ///< one guard, one restore
    /// Restores every stand-in (Sleeping::restoreAll).
    ~RestoreOnExit() { sleeping_.restoreAll(world_); }

   private:
    Sleeping& sleeping_;
    World& world_;
  };

  /// Before the passes of a step: fits the per-body state to the world's bodies (added bodies
  /// start awake; removing bodies wakes everything), wakes sleeping bodies changed or
  /// unsupported from outside, turns the others into immovable stand-ins and records the poses
  /// the step starts from.
  /// \return false when sleeping is on and no movable body is awake: the step can do nothing.
  bool begin(World& world);

  /// The wake test for one contact of a pass, just before its COLLIDE (`call` holds COLLIDE's
  /// arguments): a sleeping body hit hard enough by an awake one gets its mass back, so it
  /// takes its share of this very impulse. Does not change the contact. A BeforeCollide hook
  /// for both RESOLVECOLLISIONS and RESOLVECONTACTS (\alg{DAMPEDINTEGRATION L1-L2}).
  void beforeCollide(World& world, const ImpulseContact& contact, const CollideCall& call);

  /// After SETGEOMETRICALLYSTABLE (\alg{DAMPEDINTEGRATION L6}): each sleeping body gets back in
  /// `stable` (one flag per body) the flag it had when it fell asleep.
  void holdStability(std::vector<char>& stable) const;

  /// The remembered manifolds of pairs whose bodies both stand immovable now, which the broad
  /// phase skips, in (a, b) order; valid until the next call.
  const std::vector<ContactManifold>& skippedContacts(const World& world) const;

  /// After the passes of a step of dt s: remembers the contact graph (`contacts`, found at the
  /// end of the step, plus the skipped pairs), wakes sleeping bodies penetrated beyond the slop,
  /// restores every stand-in, counts still steps and puts to sleep the still bodies whose
  /// supports sleep or are immovable. `stable` (one flag per body) is kept for each body that
  /// falls asleep. Call only after begin() returned true.
  void end(World& world, const std::vector<ContactManifold>& contacts,
           const std::vector<char>& stable, double dt);

  /// Gives every body standing in as immovable its own mass properties back.
  void restoreAll(World& world);

  /// One flag per body of the world last stepped, 1 for a body asleep.
  const std::vector<char>& asleep() const { return asleep_; }
  /// The number of bodies asleep.
  int asleepCount() const;
  /// The number of contact manifolds remembered at the end of the last step, the skipped pairs
  /// included.
  int restingContacts() const { return static_cast<int>(resting_.size()); }

 private:
  /// What a sleeping body gives up while it stands in as immovable.
  struct MassProperties {
    double mass = 1.0;
    double invMass = 1.0;
    Vec3 IbodyInvDiag = Vec3::Ones();
  };

  void standIn(World& world, int body);
  void restore(World& world, int body);
  void wake(World& world, int body);
  bool supportedBy(const ContactManifold& contact, int upper) const;
  /// Whether body i is at rest enough to fall asleep after `steps` steps: exactly still that
  /// long, or chattering (chatter detection on) on at least one support.
  bool restsFor(int i, long steps) const;
  /// Rebuilds the index of resting_ by body (restingOf) for n bodies.
  void indexResting(std::size_t n);
  /// The indices into resting_ of body i's remembered contacts, in resting_'s order.
  struct Indices {
    const int* first;  ///< the first index
    const int* last;   ///< one past the last
    const int* begin() const { return first; }  ///< for range-for
    const int* end() const { return last; }     ///< for range-for
  };
  /// As Indices says, for body i (after indexResting).
  Indices restingOf(std::size_t i) const {
    return {restingIndex_.data() + restingStart_[i], restingIndex_.data() + restingStart_[i + 1]};
  }
  /// 1/kg: the normal velocity change per unit normal impulse of body's material point at lever
  /// arm r (m) along n, with the body's own mass properties even while it stands immovable.
  double pointInverseMass(const World& world, int body, const Vec3& r, const Vec3& n) const;

  SleepParams params_;
  double slop_;                         // FIXCONTACTCONSTRAINTS' slop, in units of ℓ
  std::vector<char> asleep_;            // per body: asleep
  std::vector<char> standing_;          // per body: standing in as immovable in this step
  std::vector<int> stillSteps_;         // per body: consecutive steps exactly still
  std::vector<BodyState> sleepState_;   // per body: the state it fell asleep with
  std::vector<char> sleepStable_;       // per body: its geometric stability when it fell asleep
  std::vector<MassProperties> saved_;   // per body: mass properties while standing in
  std::vector<BodyState> start_;        // per body: the state at the start of this step
  ChatterHistory chatter_;              // per body: the window of chatter detection
  // The contact manifolds at the end of the last step, in (a, b) order. Those of pairs that
  // both stand immovable are kept while they do: the broad phase skips such pairs, so the
  // narrow phase cannot report them again, and neither body has moved.
  std::vector<ContactManifold> resting_;
  // The index of resting_ by body, one flat list: body i's contacts are
  // restingIndex_[restingStart_[i], restingStart_[i + 1]).
  std::vector<std::size_t> restingStart_;
  std::vector<int> restingIndex_;
  // Working lists kept for their room: the contact graph end() builds, the bodies begin() finds
  // disturbed, wake()'s bodies to wake, skippedContacts()' answer.
  std::vector<ContactManifold> next_;
  std::vector<ContactManifold> remembered_;  ///< end(): the remembered manifolds still standing
  std::vector<int> disturbed_;
  std::vector<int> pending_;
  mutable std::vector<ContactManifold> skipped_;
};

}  // namespace boxsim
