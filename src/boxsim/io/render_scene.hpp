/// \file
/// The geometry render.hpp draws, with no gnuplot text in it: the fixed camera, which faces of
/// each box it sees and their shades, the ground square with its grid and the boxes' shadows,
/// and the axis ranges that keep a whole run in the picture at one zoom. render.cpp turns the
/// result into a gnuplot script. Internal to the library.
///
/// Everything here is in gnuplot coordinates (z up): world (x, y, z) becomes (x, −z, y), a
/// rotation by +90° about x, so handedness and face orientation survive the change of frame.
#pragma once

#include <limits>
#include <map>
#include <string>
#include <vector>

#include "boxsim/core/math.hpp"
#include "boxsim/io/trajectory.hpp"

/// The pure geometry behind renderScript(): shared by render.cpp and render_scene.cpp only.
namespace boxsim::render {

/// gnuplot's `set view rot_x, rot_z` first angle, degrees: the camera sits 28° above the horizon
/// (rot_x = 90° − 28°).
inline constexpr double kViewRotX = 62.0;
/// gnuplot's `set view rot_x, rot_z` second angle, degrees: the camera looks from the front
/// right, so a box at rest shows its top, its +x and its +z faces.
inline constexpr double kViewRotZ = 30.0;

/// A point on the screen, or (x, z) on the ground.
using Vec2 = Eigen::Vector2d;

/// The camera's screen axes in gnuplot coordinates for `set view kViewRotX, kViewRotZ`:
/// screen x = right·p, screen y = up·p. Unit vectors, mutually orthogonal.
struct ViewAxes {
  Vec3 right;    ///< screen x
  Vec3 up;       ///< screen y
  Vec3 towards;  ///< from the scene to the viewer
};

/// The camera axes of the fixed view: gnuplot rotates the scene about z by kViewRotZ, then about
/// the screen's x by kViewRotX, and these are the rows of that rotation.
ViewAxes viewAxes();

/// A filled polygon, corners in gnuplot coordinates (m), in order around it.
struct Polygon {
  std::vector<Vec3> corners;  ///< at least three, planar
  int rgb = 0;                ///< fill colour, 0xRRGGBB, already shaded
};

/// A line segment in gnuplot coordinates (m).
struct Segment {
  Vec3 from;  ///< one end
  Vec3 to;    ///< the other end
};

/// What one frame draws, in gnuplot coordinates.
struct FrameDrawing {
  /// Box faces turned towards the camera, in body order; gnuplot sorts them by depth.
  std::vector<Polygon> faces;
  /// Top faces of the immovable bodies too large to be boxes (floors), clipped to the ground
  /// square; drawn behind everything.
  std::vector<Polygon> grounds;
  /// Straight-down shadows of the boxes on the largest floor, drawn over it.
  std::vector<Polygon> shadows;
  /// Grid lines on the largest floor, drawn over the shadows.
  std::vector<Segment> grid;
};

/// Decides once, from every frame of a run, how large the ground square is and which immovable
/// bodies are floors rather than boxes, then draws any frame in that same way.
class SceneDrawer {
 public:
  /// Checks every frame and fixes the ground square: centred on the movable boxes' footprint over
  /// the whole run, with half side `groundHalfSize` (m) or, when that is not positive, half the
  /// footprint plus two box sizes, so boxes near the edge still stand on visible ground. An
  /// immovable body wider than the square in its first frame is a floor.
  /// `trajectory` must outlive the drawer.
  /// \throws std::invalid_argument for a frame whose pose count differs from the body count, or
  ///         a non-finite or zero pose (the message names the frame and the body).
  /// `bodyColours` gives the fill colour (0xRRGGBB, before shading) of the bodies it names;
  /// the others take the palette. \throws std::invalid_argument for a name no body has.
  SceneDrawer(const Trajectory& trajectory, double groundHalfSize,
              const std::map<std::string, int>& bodyColours = {});

  /// Draws frame `frameIndex` (0 ≤ frameIndex < frame count, not checked): every face of every
  /// box the camera sees, Lambert shaded; the floors' top faces; and, on the largest floor in
  /// view, the boxes' shadows and a grid.
  FrameDrawing draw(int frameIndex) const;

 private:
  const Trajectory& trajectory_;
  ViewAxes view_;
  Vec2 squareCentre_ = Vec2::Zero();  // (x, z) in the world, m
  double squareHalf_ = 1.0;           // m
  std::vector<bool> huge_;            // per body: drawn as a floor
  std::vector<int> colour_;           // per body: fill colour before shading
};

/// The bounds of everything drawn in a set of frames, in gnuplot coordinates and on the screen
/// (along ViewAxes::right and ViewAxes::up). Empty (low > high) until something is included.
class SceneBounds {
 public:
  /// Widens the bounds to hold every corner and grid end point of `drawing`.
  void include(const FrameDrawing& drawing);

  /// Smallest x, y, z drawn, m.
  Vec3 low = Vec3::Constant(std::numeric_limits<double>::infinity());
  /// Largest x, y, z drawn, m.
  Vec3 high = Vec3::Constant(-std::numeric_limits<double>::infinity());
  /// Smallest screen x, y drawn, m.
  Vec2 screenLow = Vec2::Constant(std::numeric_limits<double>::infinity());
  /// Largest screen x, y drawn, m.
  Vec2 screenHigh = Vec2::Constant(-std::numeric_limits<double>::infinity());

 private:
  void include(const Vec3& p);
  ViewAxes view_ = viewAxes();
};

/// Axis ranges for gnuplot. With `set view equal xyz`, equal x and y spans and screen margins,
/// gnuplot maps a point p to pixel (centre of the plot area) + side / span · (right·(p − c),
/// up·(p − c)), where side is the smaller dimension of the plot area (graph3d.c normalises the
/// range box to [−1, 1] and draws it at half the side). So the span sets the zoom and the range
/// centre c is what appears in the middle.
struct Framing {
  Vec3 centre = Vec3::Zero();  ///< centre c of the x, y and z ranges, m
  double span = 1.0;           ///< length of the x range and of the y range, m
  double zHalf = 1.0;          ///< half the length of the z range, m
};

/// The ranges that show everything in `bounds` in the middle of a plot area of `areaWidth` ×
/// `areaHeight` pixels, filling most of it, and that hold every point drawn (pm3d clips what
/// lies outside). The default Framing when `bounds` is empty.
Framing frameScene(const SceneBounds& bounds, double areaWidth, double areaHeight);

}  // namespace boxsim::render
