/// \file
/// Measures of what a filter (\thesis{§5.5}) does to a recorded run, each over a window of
/// frames: the chatter it removes, the squirm it leaves, the pops it makes, the overlaps it
/// introduces and the impacts it softens. Each measure reads the displayed poses only, so it
/// applies alike to a raw run and to its filtered versions; the comparisons (filtered minus or
/// over raw) are left to the caller.
///
/// Resting bodies: the chatter and squirm measures are meant for bodies that should stand
/// still. restingBodies() picks them from the *raw* run, so raw and filtered versions are
/// measured on the same bodies: a movable body rests over a window when, in every frame of it,
/// its position stays within RestingParams::displacementFraction × its smallest half extent of
/// its position at the window's first frame, and its orientation within RestingParams::angle of
/// the orientation there.
#pragma once

#include <cstddef>
#include <vector>

#include "boxsim/core/frame_sink.hpp"

namespace boxsim {

/// Frames [begin, end) of a trajectory.
struct FrameWindow {
  std::size_t begin = 0;  ///< first frame index
  std::size_t end = 0;    ///< one past the last frame index
};

/// The frames whose time lies in [t0, t1] s (each end widened by 1e-9 s against rounding).
/// \throws std::invalid_argument when fewer than 3 frames lie there (the second differences
///         of the measures need 3), naming the interval and the run's time span.
FrameWindow frameWindow(const Trajectory& trajectory, double t0, double t1);

/// When a body counts as resting (see the file comment).
struct RestingParams {
  /// Largest displacement from the window's first frame, as a fraction of the body's smallest
  /// half extent (0.2: 0.1 m for a unit cube, about eight times the largest jitter of the
  /// standing pyramid under the plain impulse step, 12 mm in s5_2_chatter; a tenth of the
  /// cube's edge).
  double displacementFraction = 0.2;
  /// Largest rotation from the window's first frame, rad (0.2 rad, 11°: a tilted box leaning
  /// on another still rests; a box tipping over does not).
  double angle = 0.2;
};

/// The movable bodies of `raw` that rest over `window` (indices, increasing).
/// \throws std::invalid_argument when the window lies outside the trajectory.
std::vector<std::size_t> restingBodies(const Trajectory& raw, FrameWindow window,
                                       const RestingParams& params = {});

/// Every movable body of `trajectory` (indices, increasing).
std::vector<std::size_t> movableBodies(const Trajectory& trajectory);

/// Chatter and squirm of the displayed poses of some bodies over a window.
struct MotionMeasures {
  /// Chatter of position: the mean over the bodies and the window's inner frames k of
  /// |x(k+1) − 2 x(k) + x(k−1)|², m². Zero for a body at rest or in uniform motion; a jitter
  /// alternating between +a and −a every frame gives 16 a².
  double chatterPosition = 0.0;
  /// Chatter of orientation: the same for the change of the per-frame rotation vector,
  /// |ω(k) − ω(k−1)|² with ω(k) = rotationVector(q(k), q(k+1)), rad².
  double chatterAngle = 0.0;
  /// Squirm of position: the path length per second of the pose low-passed by a centred box
  /// filter of MeasureParams::squirmHalfWidth frames, over the window, m/s: the slow motion
  /// left once the fast motion is averaged away, which a viewer sees as the body wandering.
  /// Mean over the bodies.
  double squirmPosition = 0.0;
  /// Squirm of orientation: the same for the angles turned, rad/s.
  double squirmAngle = 0.0;
  /// Displayed speed of position: the path length per second of the displayed poses as they
  /// are, frame to frame, over the window, m/s (mean over the bodies): all the motion a viewer
  /// sees of a body that should stand still, jitter and wandering together.
  double displayedSpeedPosition = 0.0;
  /// Displayed speed of orientation: the same for the angles turned, rad/s.
  double displayedSpeedAngle = 0.0;
  std::size_t bodies = 0;  ///< how many bodies the means are over (0: every field 0)
  /// The share of the displayed motion that is squirm, squirmPosition / displayedSpeedPosition
  /// (0 when nothing moves): near 0 when a body jitters back and forth about a place, near 1
  /// when all it shows is slow wandering. A low-pass filter leaves the squirm and removes the
  /// jitter, so this share, unlike the squirm itself, tells whether the motion left looks like
  /// chatter or like squirm (\thesis{§5.5}: "objects that used to chatter will often appear to
  /// squirm instead").
  double squirmSharePosition() const {
    return displayedSpeedPosition > 0.0 ? squirmPosition / displayedSpeedPosition : 0.0;
  }
};

/// Parameters of the measures.
struct MeasureParams {
  /// Half width of the low-pass the squirm measure uses, frames (6: 0.1 s either side at
  /// 60 Hz, so motion faster than about 5 Hz does not count as squirm).
  int squirmHalfWidth = 6;
};

/// Chatter and squirm of `displayed` over `window` for the bodies `bodies`.
/// \throws std::invalid_argument when the window lies outside the trajectory or holds fewer
///         than 3 frames, or a body index is out of range.
MotionMeasures motionMeasures(const Trajectory& displayed, FrameWindow window,
                              const std::vector<std::size_t>& bodies,
                              const MeasureParams& params = {});

/// Pops: the largest jump of the displayed pose from one frame to the next.
struct PopMeasure {
  /// max over the bodies and the window's frames of |x(k) − x(k−1)|, m.
  double position = 0.0;
  /// max over the bodies and the window's frames of the angle turned from frame k − 1 to k, rad.
  double angle = 0.0;
};

/// Pops of `displayed` over `window` for the bodies `bodies`. Meant for resting bodies: there
/// a raw run's largest jump is its chatter, a box filter's is smaller, and the envelope
/// filter's is the jump of a stable pose, about the envelope's radius or angle.
/// \throws std::invalid_argument as motionMeasures() for the window and bodies.
PopMeasure pops(const Trajectory& displayed, FrameWindow window, const std::vector<std::size_t>& bodies);

/// The deepest overlap of the displayed boxes.
struct OverlapMeasure {
  double boxBox = 0.0;     ///< deepest separating-axis depth of two movable boxes, m (0 if none)
  double boxGround = 0.0;  ///< deepest depth of a movable box in an immovable one, m (0 if none)
};

/// The deepest overlap (separating-axis depth, separating_axis.hpp) over the window's frames
/// and every pair of bodies. Pairs whose bounding spheres are apart are skipped.
/// \throws std::invalid_argument when the window lies outside the trajectory.
OverlapMeasure deepestOverlap(const Trajectory& trajectory, FrameWindow window);

/// The overlap a filter introduces: over the window's frames and every pair of bodies, the
/// largest amount by which the pair's overlap depth in `displayed` exceeds its depth in `raw`
/// in the same frame (depths below 0, separated boxes, count as 0), m; 0 if never positive.
/// A filter that moves a body into another where the simulation had them apart, or deeper
/// than the simulation had them, shows here; an overlap the simulation itself made does not.
/// \throws std::invalid_argument when the trajectories differ in frame or body count, or the
///         window lies outside them.
OverlapMeasure overlapIntroduced(const Trajectory& raw, const Trajectory& displayed, FrameWindow window);

/// The largest acceleration of the displayed motion: how sharp its impacts look.
struct PeakAcceleration {
  /// max |x(k+1) − 2 x(k) + x(k−1)| / Δt², m/s² (Δt from the frame times).
  double linear = 0.0;
  /// max |ω(k) − ω(k−1)| / Δt², rad/s², ω as in MotionMeasures::chatterAngle.
  double angular = 0.0;
};

/// The peak acceleration of `bodies` over the window's inner frames.
/// \throws std::invalid_argument as motionMeasures().
PeakAcceleration peakAcceleration(const Trajectory& trajectory, FrameWindow window,
                                  const std::vector<std::size_t>& bodies);

}  // namespace boxsim
