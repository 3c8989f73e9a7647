/// \file
/// Draws a recorded trajectory in 3D with gnuplot: one frame, a strip of frames, or the whole
/// run as an animation.
///
/// Every box is drawn as its faces turned towards the camera, each filled with a flat
/// Lambert shade (ambient plus diffuse from a fixed light), sorted back to front by gnuplot's
/// `pm3d depthorder`. A large immovable body (the ground) is drawn as its top face, clipped to a
/// light grey square around the scene, with a grid and straight-down shadows of the
/// boxes; smaller immovable bodies are drawn as grey boxes. The camera never moves: view angles
/// and axis ranges are computed once from every frame, so an animation does not jump.
///
/// The world is y-up and gnuplot is z-up; world (x, y, z) is drawn at gnuplot (x, −z, y), a
/// rotation by +90° about x, so handedness and face orientation survive the change of frame.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "boxsim/io/trajectory.hpp"

namespace boxsim {

/// How renderScript() and renderTrajectory() draw a trajectory.
struct RenderOptions {
  int width = 800;   ///< image width of one panel, pixels (a strip is frames × width wide)
  int height = 600;  ///< image height, pixels
  /// Frame indices to draw. Empty: frame 0 for `.png` and `.svg`, every frame for `.gif`.
  /// Several frames in a `.png` or `.svg` make a horizontal strip, one panel per frame.
  std::vector<int> frames;
  /// At most this many frames in a `.gif`; longer runs are subsampled evenly.
  int maxGifFrames = 200;
  /// Delay between `.gif` frames, s. 0: real time, from the frame times after subsampling.
  double gifDelaySeconds = 0.0;
  /// Half side of the ground square, m. 0: the boxes' footprint plus two box sizes.
  double groundHalfSize = 0.0;
  /// Text above the picture; empty for none.
  std::string title;
  /// Fill colours, 0xRRGGBB before shading, of the bodies named here; the others, movable
  /// ones cycling through the palette and immovable ones grey, as without it. A name no body
  /// has is an error (std::invalid_argument naming it), so a typo does not pass unseen.
  std::map<std::string, int> bodyColours;
};

/// The gnuplot script that draws `trajectory` into `outputPath`, data inline.
///
/// The image type follows the extension of `outputPath`: `.png` (pngcairo), `.svg` (one frame
/// or a strip) or `.gif` (an animation that loops forever, at real time unless
/// RenderOptions::gifDelaySeconds says otherwise).
/// \throws std::invalid_argument for any other extension (the message names it and the
///         supported ones), for a trajectory without frames, or for a frame whose pose count
///         differs from the body count.
/// \throws std::out_of_range for a frame index outside the trajectory (the message names the
///         valid range).
std::string renderScript(const Trajectory& trajectory, const std::string& outputPath,
                         const RenderOptions& options);

/// Draws `trajectory` into `outputPath` by running gnuplot on renderScript().
///
/// The image is written whole or not at all: gnuplot writes a temporary file beside
/// `outputPath`, which is renamed over it only when gnuplot succeeds. The gnuplot executable is
/// `gnuplot` on the PATH unless the environment variable `BOXSIM_GNUPLOT` names another.
/// \throws std::invalid_argument, std::out_of_range as renderScript().
/// \throws std::runtime_error when gnuplot fails (the message holds its standard error) or the
///         files cannot be written; no temporary file is left behind.
void renderTrajectory(const Trajectory& trajectory, const std::string& outputPath,
                      const RenderOptions& options);

}  // namespace boxsim
