/// \file
/// Chatter detected from history, the thesis' future work (\thesis{§6.3.1}: "using data from
/// previous time steps to determine whether an object is chattering"). The thesis gives no rule;
/// the rule here is ours (ChatterHistory states it). Sleeping (sleeping.hpp) asks it, when
/// SleepParams::chatterDetection is on, which awake bodies may fall asleep although their
/// momenta are not exactly zero.
#pragma once

#include <vector>

#include "boxsim/core/rigid_body.hpp"

namespace boxsim {

/// Per body, what the last steps did: the pose and kinetic energy of each step of a sliding
/// window.
///
/// A body *chatters* (§5.2's "chattering objects", seen over time) when, over the last `window`
/// steps, its motion went nowhere and drew on no energy:
/// 1. its pose stayed within an envelope of the window's first pose: its centre within
///    r = `envelope` ℓ (ℓ its smallest half extent) and its orientation within r / h (h its
///    half diagonal), the envelope filter's default (\thesis{§5.5});
/// 2. gravity did no work on it: its centre sank along g over the window by no more than the
///    contact slop (`slop` ℓ, FIXCONTACTCONSTRAINTS' allowance for a resting contact to settle);
/// 3. its kinetic energy is not growing: the last step's is no more than the largest of the
///    window's first half.
///
/// Chatter is contact passes that kick a resting box and DAMPENOBJECTS that halves the kick, the
/// pose snap holding it: no net motion, no energy in. A box tipping over a support's edge can
/// stay within the envelope for a while, damping holding its kinetic energy level, but it sinks
/// as it tips: (2) keeps it awake. A box starting to fall gathers energy: (3). A box gliding
/// away leaves the envelope: (1).
class ChatterHistory {
 public:
  /// `envelope` is SleepParams::chatterEnvelope and `slop` FixContactParams::slop, both in
  /// units of ℓ, > 0.
  ChatterHistory(double envelope, double slop) : envelope_(envelope), slop_(slop) {}

  /// Fits the history to n bodies: bodies beyond n are forgotten, new ones start empty.
  void resize(std::size_t n);
  /// Forgets the history of body i: its window starts again at its next record().
  void reset(std::size_t i);
  /// Records body i as it ends a step, under gravity `g` (m/s²), with a window of the last
  /// `window` steps (>= 1), and decides whether it chatters.
  void record(std::size_t i, const RigidBody& body, const Vec3& g, long window);
  /// Whether body i chattered over the window of its last record() (the rule of the class).
  bool chatters(std::size_t i) const { return i < bodies_.size() && bodies_[i].chatters; }

 private:
  /// One step of a body's window.
  struct Sample {
    Vec3 x;         // m, centre
    Quat q;         // orientation
    double energy;  // J, kinetic energy
  };
  struct Body {
    std::vector<Sample> window;  // the last steps, oldest first
    bool chatters = false;
  };
  /// The rule of the class over a full window of `body` (its half extents give ℓ and h).
  bool judge(const std::vector<Sample>& window, const RigidBody& body, const Vec3& g) const;

  double envelope_;
  double slop_;
  std::vector<Body> bodies_;
};

}  // namespace boxsim
