/// \file
/// Scene files: JSON describing the ground, gravity, restitution, friction, the broad phase, bodies and
/// named builders.
/// The schema is documented in docs/scene_format.md; every error names the file, the line and
/// column (malformed JSON) or the JSON path (bad values), and what to change.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "boxsim/core/world.hpp"

namespace boxsim {

/// A scene that could not be loaded. what() reads "FILE: LOCATION: problem. Fix: ...".
class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A loaded scene: the world and where each body came from.
struct Scene {
  World world;  ///< the bodies, gravity, restitution and broad phase the scene describes
  std::string source;       ///< file name (or the name given to parseScene)
  std::string description;  ///< the scene's "description", if any
  /// The scene's "friction": every body's and the ground's unless they give their own.
  Friction friction;
  /// For each body of world, the JSON path it came from ("/bodies/0", "/builders/1 (tower
  /// box 3)", "/ground"), for error messages.
  std::vector<std::string> origins;
};

/// Parses and validates scene text. `source` names it in error messages; loadScene() reads a
/// file and calls this, so the command line and this function accept exactly the same scenes.
/// Checks: well-formed JSON; only known keys; numbers finite; masses, extents, counts and
/// sizes positive; numbers in the range where the physics stays within double precision
/// (masses in [1e-6, 1e6] kg; half extents, cube sizes, spacings and ground sizes in
/// [1e-6, 1e6] m; coordinates and gaps, speeds, angular speeds and gravity of magnitude at
/// most 1e6 m, m/s, rad/s and m/s²); quaternions non-zero; names free of white space and
/// unique; "friction" (scene, ground, body or builder) a coefficient in [0, 10] or
/// {"static", "dynamic"} with dynamic <= static; "broad_phase", when given, "all_pairs" or "sweep_and_prune" (the default); no two
/// boxes overlapping at the start (touching is allowed). Throws SceneError.
Scene parseScene(const std::string& text, const std::string& source);

/// Reads and parses a scene file; throws SceneError (also when the file cannot be read).
Scene loadScene(const std::string& path);

}  // namespace boxsim
