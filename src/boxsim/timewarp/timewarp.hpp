/// \file
/// The modified timewarp of \thesis{§5.1} and \alg{A.1}: every body keeps two states, a valid
/// state at its own valid time and a test state at the end of the frame. Collisions found
/// between test states are timed by bisection and resolved in time order, and only the two
/// bodies of a collision are rewound and integrated again (\thesis{§2.4.3}: Mirtich's timewarp,
/// synchronised every frame). SIMPLESYNCTIMEWARP trusts the collisions it finds;
/// SAFERSYNCTIMEWARP first checks the bodies near each collision for an earlier one it missed;
/// the swept variant finds pairs by the swept bounds of their motion and times them by
/// conservative advancement, so a fast body cannot pass through another unseen (\thesis{§5.1},
/// Fig. 5.1). All three end with FIXINTERPENETRATION (\thesis{§4.4}, fix_contact_constraints.hpp).
#pragma once

#include <string>
#include <vector>

#include "boxsim/collision/separating_axis.hpp"
#include "boxsim/core/enum_names.hpp"
#include "boxsim/core/integrator.hpp"
#include "boxsim/core/stepper.hpp"
#include "boxsim/impulse_damped/impulse_params.hpp"

namespace boxsim {

/// Which procedure of \alg{A.1} a TimewarpStepper runs.
enum class TimewarpVariant {
  Simple,  ///< \alg{SIMPLESYNCTIMEWARP}
  Safer,   ///< \alg{SAFERSYNCTIMEWARP}
  Swept,   ///< SIMPLESYNCTIMEWARP with swept-volume pair finding (\thesis{§5.1})
};

/// The method name of a variant: "timewarp_simple", "timewarp_safer", "timewarp_swept".
std::string timewarpMethodName(TimewarpVariant variant);

/// The method names of the variants.
inline constexpr EnumNames<TimewarpVariant, 3> kTimewarpMethodNames{{
    {TimewarpVariant::Simple, "timewarp_simple"},
    {TimewarpVariant::Safer, "timewarp_safer"},
    {TimewarpVariant::Swept, "timewarp_swept"},
}};

/// Parameters of the modified timewarp.
struct TimewarpParams {
  /// The procedure: simple, safer or swept.
  TimewarpVariant variant = TimewarpVariant::Simple;
  /// `resolution` of \alg{A.1} (s, > 0): bisection stops when the bracket of a collision time
  /// is narrower than this. 1e-5 s, as the basic colliding technique's time tolerance.
  double resolution = 1e-5;
  /// m, >= 0: a pair "intersects" when its separating-axis depth exceeds this (the
  /// techniques' kIntersectionDepthTolerance, as TimeOfImpactParams::depthTolerance).
  double depthTolerance = kIntersectionDepthTolerance;
  /// m, > 0: the swept variant's conservative advancement stops when the gap between two
  /// boxes is below this, and takes that instant as their collision time.
  double sweptGap = 1e-5;
  /// m, >= 0: findNearObjects of SAFERSYNCTIMEWARP takes every body whose test-state bounds,
  /// widened by this, overlap the colliding pair's. 0.5 m, half a unit box.
  double nearMargin = 0.5;
  /// Collisions one frame may resolve; past it the rest of the frame is dropped, every body
  /// stopping at the last instant found apart before the earliest collision left (or at its
  /// valid time, if later), and StepStats::limitReached is set (as
  /// BasicCollidingParams::maxEventsPerStep).
  int maxEventsPerStep = 1000;
  /// Integration between collisions (integrateForward of \alg{A.1}).
  /// DEVIATION(\thesis{§6.2}, \alg{A.1} integrateForward): the thesis integrated with forward
  /// Euler; the default is semi-implicit Euler, as the basic technique's, for the reason
  /// BasicCollidingParams gives (forward Euler adds energy to every bounce).
  Integrator integrator = Integrator::SemiImplicitEuler;
  /// FIXINTERPENETRATION at the end of the frame (\alg{SIMPLESYNCTIMEWARP L22},
  /// \alg{SAFERSYNCTIMEWARP L33}), with the slop and nudge of \alg{A.2}'s FIXCONTACTCONSTRAINTS,
  /// which implements \thesis{§4.4}.
  bool fixInterpenetration = true;
  /// Slop and nudge of FIXINTERPENETRATION, in units of the upper body's smallest half extent.
  FixContactParams fix;
  /// m: pairs closer than this count as contacts in StepStats, and FIXINTERPENETRATION gathers
  /// contacts with it.
  double contactMargin = 1e-3;
};

/// One collision the timewarp resolved: when, and which bodies.
struct TimewarpEvent {
  double time = 0.0;  ///< s after the start of the frame
  int a = -1;         ///< body index, a < b
  int b = -1;         ///< body index
};

/// The modified timewarp as a Stepper.
class TimewarpStepper final : public Stepper {
 public:
  /// A stepper with the given parameters; throws std::invalid_argument on out-of-range ones.
  explicit TimewarpStepper(const TimewarpParams& params = {});
  std::string name() const override { return timewarpMethodName(params_.variant); }
  std::map<std::string, std::string> parameters() const override;
  /// At most TimewarpParams::maxEventsPerStep collisions a frame, in words.
  std::string workLimit() const override;
  /// One frame of dt s: \alg{SIMPLESYNCTIMEWARP}(t, dt, resolution) or
  /// \alg{SAFERSYNCTIMEWARP}, or the swept variant. StepStats counts events, bisection steps,
  /// body integrations and body roll-backs.
  StepStats step(World& world, double dt) override;
  /// The collisions of the last frame, in the order they were resolved.
  const std::vector<TimewarpEvent>& lastEvents() const { return events_; }

 private:
  TimewarpParams params_;
  std::vector<TimewarpEvent> events_;
};

}  // namespace boxsim
