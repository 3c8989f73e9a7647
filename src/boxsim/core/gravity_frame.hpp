/// \file
/// A world stepped in a frame where its gravity points down (along −y), for a technique that
/// takes +y as up.
///
/// The thesis' damped integration reads "up" as +y throughout (\alg{A.2}: DAMPENOBJECTS'
/// vertical velocity and the face perpendicular to gravity, FIXCONTACTCONSTRAINTS' upward
/// nudge and its order by height, SETGEOMETRICALLYSTABLE's bottom corners), and boxsim's world
/// is y-up (docs/conventions.md). A scene may still give gravity any direction, as a z-up user
/// does with (0, 0, −9.81). The laws of motion do not depend on the frame they are written in,
/// so such a world is stepped turned by the rotation R that takes its gravity to −y: every
/// body's x, q, P and L turned by R, gravity (0, −|g|, 0), the step taken there, and the bodies
/// turned back by Rᵀ. The turned world is kept from step to step, so the technique's memory of
/// poses (sleeping's still poses, kept narrow phases) holds there as it does in a y-up world;
/// only what the caller changed between steps is turned again.
#pragma once

#include <vector>

#include "boxsim/core/math.hpp"
#include "boxsim/core/world.hpp"

namespace boxsim {

/// Whether a technique that takes +y as up can step a world with `gravity` (m/s²) as it is:
/// gravity along −y (x and z exactly 0, y <= 0) or none.
inline bool gravityPointsDown(const Vec3& gravity) {
  return gravity.x() == 0.0 && gravity.z() == 0.0 && gravity.y() <= 0.0;
}

/// The rotation that takes the direction of `gravity` (m/s², finite and non-zero) to −y: the
/// shortest one (about the axis perpendicular to both), or a half turn about x when gravity
/// points along +y. Throws std::invalid_argument for zero or non-finite gravity.
Quat turnGravityDown(const Vec3& gravity);

/// A world kept turned so that its gravity points along −y (the file comment). Use: enter()
/// before each step, step the world it returns, leave() after it.
class GravityFrame {
 public:
  /// `world` turned so that its gravity is (0, −|g|, 0), to be stepped: built anew for a new
  /// world (another gravity or number of bodies), else the world of the last step with the
  /// bodies the caller changed since leave() (state, mass, extents, mobility or friction)
  /// turned again and restitution and broad phase copied. `world.gravity` must be finite and
  /// non-zero (turnGravityDown). The reference stays valid until the next enter().
  World& enter(const World& world);
  /// Writes the bodies the step moved back into `world` (the world given to enter()), turned
  /// back, with their derived quantities; the others are left bit for bit as they were.
  void leave(World& world);

 private:
  /// Body i of the turned world from `body` of the caller's: x, q, P and L turned by turn_.
  void turnIn(std::size_t i, const RigidBody& body);

  bool built_ = false;
  Vec3 gravity_ = Vec3::Zero();  ///< m/s², the caller's gravity the frame was built for
  Quat turn_ = Quat::Identity(); ///< R: the caller's frame to the turned one
  World turned_;                 ///< the world as stepped
  std::vector<BodyState> entered_;   ///< per body, its turned state when the step began
  std::vector<RigidBody> handedBack_;  ///< per body, the caller's body after the last leave()
};

}  // namespace boxsim
