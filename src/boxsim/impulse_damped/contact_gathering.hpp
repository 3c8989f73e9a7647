/// \file
/// gatherCollisions of RESOLVECOLLISIONS and RESOLVECONTACTS (\alg{RESOLVECOLLISIONS L2-L3, L6},
/// \alg{RESOLVECONTACTS L2-L3, L6}):
/// the contacts between bodies moved to their predicted positions x + Δt v'. Two ways to find
/// them, chosen by ImpulseParams::gathering:
///
/// - EveryPass, \alg{A.2} as written (and Guendelman et al. 2003, §7): every pass moves each
///   body to its predicted pose (integrateObjectPositions, predicted_positions.hpp), runs the
///   broad and narrow phase there (findContacts), and moves it back
///   (revertToOriginalPositions). ContactGathering::begin() holds all of it.
/// - OncePerStep, the default: the same contacts found mostly once per step, slow pairs
///   predicted from one narrow phase at the current poses and fast bodies moved as written
///   (once_per_step_gathering.hpp, which states what differs).
///
/// Where COLLIDE acts, in both modes. \alg{A.2} collides the pairs while the bodies stand at
/// their predicted poses and reverts them after (\alg{RESOLVECOLLISIONS L4-L6}). Here begin() puts
/// every body back before it returns; each contact keeps the lever arms r' = p - x' of the
/// poses it was found at (ImpulseContact::ra, rb), so the impulse's linear and angular parts,
/// j n and r' × j n, are those of \alg{A.2}. What changes is the inverse inertia the impulse is
/// computed with: the current pose's I⁻¹(q), giving ω = I⁻¹(q) L, where \alg{A.2} has the
/// predicted pose's I⁻¹(q') and ω' = I⁻¹(q') L.
///
///   DEVIATION(RESOLVECOLLISIONS L4-L6, RESOLVECONTACTS L4-L6): revertToOriginalPositions
///   before COLLIDE instead of after. The state holds the current orientation q, and its kinetic
///   energy is ½ P·v + ½ L·I⁻¹(q) L; an impulse computed with I⁻¹(q') removes energy measured
///   with I⁻¹(q'), and the angular momentum it leaves can hold more energy at q than the step
///   began with (on a fast-spinning plate, +31 kJ in a step: chapters/impulse_damped/README.md;
///   regression test "A fast-spinning thin plate striking the ground does not leave with more
///   energy", stress_test.cpp). With velocity and impulse measured with the same lever arm and
///   the state's inertia, the impulse changes the energy by ½ j (1 - e) v⁻ <= 0
///   (newtonian_impulse.hpp). The velocity it stops is also the one the step moves with: the
///   position update turns the body by Δt ω with ω = I⁻¹(q) L held, which carries the material
///   point at x + r to x' + r' arriving with velocity v + ω × r', the approach COLLIDE now sees.
#pragma once

#include <utility>
#include <vector>

#include "boxsim/collision/contact.hpp"
#include "boxsim/core/newtonian_impulse.hpp"
#include "boxsim/core/world.hpp"
#include "boxsim/impulse_damped/contact_islands.hpp"
#include "boxsim/impulse_damped/contact_normal.hpp"
#include "boxsim/impulse_damped/impulse_params.hpp"
#include "boxsim/impulse_damped/once_per_step_gathering.hpp"
#include "boxsim/impulse_damped/predicted_positions.hpp"

namespace boxsim {

/// The working lists of COLLIDE's loop in dependency levels (impulse_pass.hpp, "Threads"),
/// kept from pass to pass for their room.
struct CollideLevels {
  std::vector<int> lastLevel;     ///< per body: one more than its last contact's level
  std::vector<int> level;         ///< per contact: its level
  std::vector<int> body;          ///< per contact: its movable body (the island's)
  std::vector<int> start;         ///< contacts of level l are byLevel[start[l], start[l + 1])
  std::vector<int> next;          ///< the counting sort's fill cursors
  std::vector<int> byLevel;       ///< contact indices by level
  std::vector<FrictionSum*> sums;  ///< per contact: its pair's friction sums, or null
  std::vector<double> impulse;    ///< per contact: COLLIDE's impulse, N s
  std::vector<char> changed;      ///< per contact: whether COLLIDE changed anything
  std::vector<char> impact;       ///< per contact, when impacts are counted: whether an impact
};

/// gatherCollisions at predicted positions, pass after pass, in either mode of the file
/// comment. It owns the contact-normal model (\thesis{§3.3.2}), whose memory of closest faces
/// runs from step to step. Use: for every pass, begin() then end(); once per step, endStep().
class ContactGathering {
 public:
  /// Gathering with the given parameters (mode, normal model, widening). Throws
  /// std::invalid_argument for an exact reach or widening out of range, or an integrator other
  /// than SemiImplicitEuler and SplitRotation.
  explicit ContactGathering(const ImpulseParams& params = {});

  /// RESOLVECOLLISIONS / RESOLVECONTACTS L2-L3 of a pass: the contacts at the positions predicted with v' = v (+ g Δt
  /// for movable bodies under VelocityPlusGravity), every pair closer than `margin` m, one
  /// ImpulseContact per pair in a fixed order, with the lever arms of its material points where
  /// the bodies stand: every body is back at its pose before the call when this returns (the
  /// file comment, "Where COLLIDE acts"; with ImpulseParams::commonLeverPoint, from the current
  /// centres to one point, the midpoint of the two). The result stays valid until the next call.
  std::vector<ImpulseContact>& begin(World& world, double dt, GravityMode predict,
                                     double margin);
  /// OncePerStep: the step's narrow phase at the current poses and its candidate pairs
  /// (once_per_step_gathering.hpp), which the first begin() of the step would otherwise find,
  /// with the same arguments; nothing under EveryPass. Lets a caller time it apart from the
  /// passes.
  void beginStep(const World& world, double dt, GravityMode predict, double margin);
  /// Ends a pass. revertToOriginalPositions (\alg{RESOLVECOLLISIONS L6}) already happened in
  /// begin().
  void end(World& world);
  /// Ends the step: the closest faces seen become the previous step's, and the cached contacts
  /// are dropped (the step moves the bodies).
  void endStep();

  /// candidatePairs(world, margin) for the bodies where they stand after the step's passes
  /// (FIXCONTACTCONSTRAINTS, \alg{DAMPEDINTEGRATION L5}), taken from the step's candidates instead of a
  /// broad phase (StepCandidates::pairsAt). Returns false, leaving `pairs` as it was, when the
  /// step's candidates cannot tell: EveryPass, no passes since endStep, bodies whose mobility
  /// changed since the sweep, a margin wider than the sweep's, or many bodies outside their
  /// swept bounds.
  bool stepPairs(const World& world, double margin, std::vector<std::pair<int, int>>& pairs) const;

  /// OncePerStep: the islands of the step's candidate pairs (contact_islands.hpp), kept up to
  /// date pass by pass; a pass skips the bodies of settled islands (they stand, move and touch
  /// as in the pass that settled them). Null under EveryPass, which has no candidates.
  ContactIslands* islands() {
    return params_.gathering == ContactGatheringMode::OncePerStep ? &once_.islands() : nullptr;
  }

  /// OncePerStep: the sleepers, which join their partners' islands
  /// (OncePerStepGathering::setSleepers); nothing under EveryPass.
  void setSleepers(const std::vector<char>* asleep) {
    sleepers_ = asleep;
    once_.setSleepers(asleep);
  }
  /// OncePerStep with a predicted anchor: the bodies touching another at the step's start (one
  /// flag per body; OncePerStepGathering::setTouching), or null: every fast body is anchored.
  void setTouching(const std::vector<char>* touching) { once_.setTouching(touching); }
  /// Where the work the passes' threads share is measured (ParallelWork; benches), or null:
  /// none. The pointer must outlive the gathering's use of it.
  void setParallelWork(ParallelWork* work) {
    work_ = work;
    once_.setParallelWork(work);
  }
  /// What setParallelWork gave, or null.
  ParallelWork* parallelWork() const { return work_; }
  /// The sleepers given to setSleepers (one flag per body), or null.
  const std::vector<char>* sleepers() const { return sleepers_; }
  /// ImpulseParams::threads of the parameters this gathering was made with.
  int threads() const { return params_.threads; }
  /// ImpulseParams::parallelContacts of those parameters.
  int parallelContacts() const { return params_.parallelContacts; }
  /// The working lists of COLLIDE's loop in dependency levels, kept with the gathering.
  CollideLevels& collideLevels() { return collideLevels_; }
  /// Counts a pass whose COLLIDE ran in dependency levels (levelPasses()).
  void countLevelPass() { ++levelPasses_; }
  /// Passes since construction whose COLLIDE ran in dependency levels on several threads.
  long levelPasses() const { return levelPasses_; }

  /// The normal model and its memory, for contacts gathered outside the passes.
  ContactNormalTracker& normals() { return normals_; }
  /// The narrow phases of the step kept for the poses they ran at (KeptNarrowPhase), for the
  /// narrow phases a step runs outside the passes (FIXCONTACTCONSTRAINTS); kept until the step
  /// after the one that last asked for them.
  KeptNarrowPhase& kept() { return once_.kept(); }
  /// As kept(), read only: its counters, for tests and benches.
  const KeptNarrowPhase& kept() const { return once_.kept(); }
  /// Narrow phases run since construction (OncePerStep: cache builds), for tests and benches.
  long narrowPhases() const { return once_.narrowPhases(); }
  /// OncePerStep: narrow phases of pairs with a fast body at the poses of a pass, since
  /// construction, for tests and benches.
  long passNarrowPhases() const { return once_.passNarrowPhases(); }
  /// OncePerStep: one-axis checks that answered for such a test (separatedBeyond), since
  /// construction, for tests and benches.
  long passAxisChecks() const { return once_.passAxisChecks(); }
  /// OncePerStep: bodies that sat a pass out because their island was settled (islands()),
  /// summed over the passes since construction, for tests and benches.
  long skippedBodyPasses() const { return once_.skippedBodyPasses(); }
  /// OncePerStepGathering::parallelTestPasses().
  long parallelTestPasses() const { return once_.parallelTestPasses(); }

 private:
  ImpulseParams params_;
  const std::vector<char>* sleepers_ = nullptr;  ///< setSleepers()
  ParallelWork* work_ = nullptr;                 ///< setParallelWork()
  CollideLevels collideLevels_;                  ///< collideLevels()
  long levelPasses_ = 0;                         ///< levelPasses()
  ContactNormalTracker normals_;
  std::vector<ImpulseContact> contacts_;
  OncePerStepGathering once_;
};

}  // namespace boxsim
