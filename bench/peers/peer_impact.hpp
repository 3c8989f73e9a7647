/// \file
/// The impact of the shot pyramids' projectile (Fig. 6.6) under every engine with the same
/// Coulomb friction: how fast the box it strikes leaves and over how many boxes the shot's
/// momentum is shared in the step of the impact. An independent check of boxsim's impacts with
/// friction against Bullet's and ODE's (docs/shot_impact.md, written by `boxsim_peers
/// --impact`).
#pragma once

#include <string>
#include <vector>

#include "peer_engine.hpp"
#include "peer_run.hpp"

namespace boxsim::peers {

/// m/s: a change of velocity in one step above this is the impact's (for the projectile, beyond
/// gravity's g Δt; for a box of the target, it was set moving): far above what contact at rest
/// changes in a step under any of the engines, far below what the shot changes.
constexpr double kImpactSpeed = 0.3;
/// A box counts as knocked out of place at the end when it moved farther than this (m) from
/// where it stood when the projectile was launched.
constexpr double kMovedDistance = 0.1;

/// What one engine made of the shot of one scene.
struct ImpactMeasures {
  bool found = false;          ///< the projectile set some box moving before the scene's end
  double time = 0.0;           ///< s, the end of the impact's step
  /// The box of the target whose velocity the impact's step changed most (the struck box).
  int struckBody = -1;
  double struckSpeed = 0.0;    ///< m/s, its speed at the end of that step
  double struckSpeedLater = 0.0;  ///< m/s, its speed 3 steps later
  /// Boxes of the target whose velocity that step changed by more than kImpactSpeed.
  int moving = 0;
  double projectileBefore = 0.0;  ///< m/s, the projectile's speed at the end of the step before
  double projectileAfter = 0.0;   ///< m/s, its speed at the end of the impact's step
  /// N s: how much that step changed the target's momentum |Σ m v|: what the shot gave it.
  double delivered = 0.0;
  int movedAtEnd = 0;  ///< boxes of the target farther than kMovedDistance from their start
};

/// Runs `spec` (a scene with one launched box, the projectile) once under `engine` with steps
/// of dt s and measures the impact: the first step after the launch that changes the
/// projectile's velocity by more than kImpactSpeed beyond gravity's g Δt; the target is every
/// movable box but the projectile. Throws
/// std::invalid_argument when the scene launches no box or more than one.
ImpactMeasures measureImpact(const SceneSpec& spec, PeerEngine& engine, double dt);

/// One engine's impact on one scene, for the page.
struct ImpactRow {
  std::string scene;   ///< SceneSpec::label()
  std::string engine;  ///< PeerEngine::name()
  ImpactMeasures measures;
};

/// The page: how it is measured, then one table of every row. `stampText` is stamp()'s block,
/// `command` the command line that wrote it, `friction` the Coulomb coefficient every engine ran
/// with.
std::string impactPage(const std::vector<ImpactRow>& rows, double friction,
                       const std::string& stampText, const std::string& command);

}  // namespace boxsim::peers
