/// \file
/// The box filter of \thesis{§5.5}: a low-pass filter over recorded poses. Each displayed pose
/// is the mean of the poses in a window of frames around it, so the frame-to-frame jitter of a
/// chattering body averages out, at the price of slow residual motion (squirm), softened
/// impacts and possible new overlaps that the thesis names.
///
/// Two forms:
/// - boxFilter() filters a whole recorded run offline, with the window centred on each frame:
///   frame k shows the mean of frames k − H … k + H (H = BoxFilterParams::halfWidth; H = 2 is
///   the thesis' two neighbouring frames on each side). It does not delay anything.
///   BoxFilterStage computes the same frames, bit for bit, from a run streamed frame by frame,
///   holding only the window.
/// - CausalBoxFilter runs beside a simulation, as the thesis' last paragraph of §5.5 proposes:
///   it keeps the last 2H + 1 poses of each body and shows, at the newest frame k, the mean of
///   frames k − 2H … k, which is the centred filter's frame k − H. The display lags the
///   simulation by H frames (H Δt, 33 ms at H = 2 and 60 Hz).
///
/// Positions are averaged per coordinate; orientations by averageOrientations() (quaternions
/// sign-aligned with the window's centre, then averaged and normalised; Markley's eigenvector
/// average as an option). Immovable bodies are copied unchanged. Frame times, energies and
/// counters are kept as recorded: a trajectory carries no masses, so the energy of the filtered
/// motion cannot be recomputed from it, and the columns describe the simulation, not the
/// picture.
#pragma once

#include <deque>
#include <map>
#include <string>
#include <vector>

#include "boxsim/filtering/orientation_average.hpp"
#include "boxsim/core/frame_sink.hpp"

namespace boxsim {

/// Parameters of the box filter.
struct BoxFilterParams {
  /// H, frames on each side of the centre frame; the window holds 2H + 1 frames (2: the
  /// thesis' two neighbouring frames on each side). 0 leaves the poses unchanged. ≥ 0.
  int halfWidth = 2;
  /// How the orientations of a window are averaged.
  OrientationAverage orientationAverage = OrientationAverage::SignAlignedMean;
};

/// Checks the parameters; throws std::invalid_argument naming the parameter and the fix
/// (halfWidth < 0).
void validateBoxFilterParams(const BoxFilterParams& params);

/// The run `trajectory` box-filtered offline (\thesis{§5.5}), window centred on each frame.
///
/// A position is the mean of the window's positions: their sum in frame order, divided by
/// their number. (GSL's moving mean, gsl_movstat_mean, is the tests' reference; it agrees to
/// rounding.) Ends: truncated windows, so near the first and the last frame the window holds
/// only the frames that exist (frame 0 averages frames 0 … H). A body already at rest there is
/// unaffected; a body moving at the start or the end of the run is drawn up to H/2 frames of
/// its motion towards the inside of the run at the first and last frames. Away from the ends
/// (H ≤ k < n − H) a motion linear in time passes unchanged up to rounding. Orientations use
/// the same truncated windows, each averaged with the centre frame as the sign reference.
///
/// The frame count, the frame times, the body count and every non-pose column are those of the
/// input. The result's header (`meta`) adds `filter` (`box`, appended after any filter
/// already named there with ", then"), `box_half_width`, `box_orientation_average` and
/// `box_ends`.
/// \throws std::invalid_argument for bad parameters (validateBoxFilterParams()) or a frame
///         whose pose count differs from the body count.
Trajectory boxFilter(const Trajectory& trajectory, const BoxFilterParams& params = {});

/// boxFilter() as a stage of a streamed run: frames come in one at a time, and frame k goes on
/// to `next` once frame k + H has come in (the last H frames in finish()), each equal bit for
/// bit to boxFilter()'s frame k (boxFilter() is this stage fed a whole run). It holds the last
/// 2H + 1 frames, however many frames pass.
class BoxFilterStage final : public FrameSink {
 public:
  /// A stage in front of `next` (which must outlive it).
  /// \throws std::invalid_argument for bad parameters (validateBoxFilterParams()).
  BoxFilterStage(const BoxFilterParams& params, FrameSink& next);
  /// Begins `next` with `meta` plus the filter's header lines (as boxFilter() adds them).
  void begin(const std::map<std::string, std::string>& meta,
             const std::vector<TrajectoryBody>& bodies) override;
  /// Takes the next frame; passes on the frame H frames earlier, filtered, once it exists.
  /// \throws std::invalid_argument when the frame's pose count differs from the body count.
  void push(const TrajectoryFrame& frame) override;
  /// Passes on the last H frames, filtered over their truncated windows, and finishes `next`.
  void finish() override;

 private:
  BoxFilterParams params_;
  FrameSink& next_;
  std::vector<TrajectoryBody> bodies_;
  std::deque<TrajectoryFrame> window_;   // the last 2H + 1 frames, oldest first
  long received_ = 0;                    // frames pushed so far

  void emit(long k);
};

/// The box filter for real time (\thesis{§5.5}, last paragraph): it stores the last 2H + 1
/// frames of poses and turns the newest frame into the pose to display, the mean over the
/// stored frames (a trailing window). Once the window is full its output at frame k equals
/// boxFilter()'s frame k − H: the display lags by H frames. Before that (k < 2H) it averages
/// frames 0 … k; for H ≤ k < 2H that is still boxFilter()'s truncated frame k − H.
/// Orientations are averaged with frame max(0, k − H) as the sign reference, exactly as
/// boxFilter() does for the frame it matches; positions are the same sums in the same order:
/// the two agree bit for bit.
class CausalBoxFilter {
 public:
  /// A filter for the bodies `bodies` (immovable ones pass unchanged).
  /// \throws std::invalid_argument for bad parameters (validateBoxFilterParams()).
  explicit CausalBoxFilter(std::vector<TrajectoryBody> bodies, const BoxFilterParams& params = {});

  /// Stores the newest frame and returns it with every movable body's pose replaced by the
  /// mean over the stored frames; time, energies and counters as in `newest`.
  /// \throws std::invalid_argument when the frame's pose count differs from the body count.
  TrajectoryFrame push(const TrajectoryFrame& newest);

  /// The display's delay, frames: H.
  int lag() const { return params_.halfWidth; }

 private:
  std::vector<TrajectoryBody> bodies_;
  BoxFilterParams params_;
  std::deque<TrajectoryFrame> window_;  // the last 2H + 1 frames, oldest first
};

}  // namespace boxsim
