/// \file
/// The envelope filter of \thesis{§5.5}: every movable body has a stable pose, which is what is
/// displayed. The stable pose stays put while the simulated pose remains inside an envelope
/// around it, and jumps to the simulated pose as soon as the body leaves the envelope. A body
/// that chatters in place is shown perfectly still; a body that moves further than the envelope
/// in every frame is shown exactly as simulated, with no lag. The cost is the pop the thesis
/// names: a body creeping slowly is shown standing, then jumping by about one envelope.
///
/// The envelope is a ball of radius r around the stable position together with a cone of
/// half-angle θ around the stable orientation: the body leaves it when its position is more
/// than r from the stable position, or its orientation is rotated by more than θ from the
/// stable orientation. Each frame depends only on the frames before it, so the filter is
/// causal by nature; envelopeFilter() runs CausalEnvelopeFilter over the recording, and
/// EnvelopeFilterStage over a run streamed frame by frame.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "boxsim/core/frame_sink.hpp"
#include "boxsim/filtering/envelope.hpp"

namespace boxsim {

/// Parameters of the envelope filter. An empty value takes a per-body default from the body's
/// size.
struct EnvelopeFilterParams {
  /// r, m, ≥ 0: how far the position may stray from the stable position. Empty:
  /// kEnvelopeRadiusFraction × the body's smallest half extent.
  std::optional<double> radius;
  /// θ, rad, ≥ 0: how far the orientation may turn from the stable orientation. Empty: r / |h|
  /// with h the body's half extents (|h|, the half diagonal, is the distance of its corners from
  /// its centre), the turn that moves a corner by about r, so both bounds allow the same visible
  /// motion.
  std::optional<double> angle;
};

/// Checks the parameters; throws std::invalid_argument naming the parameter and the fix (a
/// radius or angle that is negative or not finite).
void validateEnvelopeFilterParams(const EnvelopeFilterParams& params);

/// The envelope filter for real time (\thesis{§5.5}): it holds each movable body's stable pose
/// and turns every new frame into the poses to display. The stable poses start at the first
/// frame pushed.
class CausalEnvelopeFilter {
 public:
  /// A filter for the bodies `bodies` (immovable ones pass unchanged).
  /// \throws std::invalid_argument for bad parameters (validateEnvelopeFilterParams()).
  explicit CausalEnvelopeFilter(std::vector<TrajectoryBody> bodies,
                                const EnvelopeFilterParams& params = {});

  /// Updates every movable body's stable pose (replaced by the frame's pose when the body is
  /// more than radius(b) from it or turned by more than angle(b)) and returns the frame with
  /// the stable poses in place of the movable bodies' poses; time, energies and counters as in
  /// `frame`.
  /// \throws std::invalid_argument when the frame's pose count differs from the body count.
  TrajectoryFrame push(const TrajectoryFrame& frame);

  /// The envelope radius of body b, m.
  double radius(std::size_t b) const { return envelope_.at(b).radius(); }
  /// The envelope angle of body b, rad.
  double angle(std::size_t b) const { return envelope_.at(b).angle(); }

 private:
  std::vector<TrajectoryBody> bodies_;
  std::vector<Envelope> envelope_;  // per body
  std::vector<Vec3> stableX_;
  std::vector<Quat> stableQ_;
  bool started_ = false;
};

/// envelopeFilter() as a stage of a streamed run: every frame goes on to `next` as soon as it
/// comes in, with the stable poses of a CausalEnvelopeFilter, so the stage holds one stable
/// pose per body however many frames pass.
class EnvelopeFilterStage final : public FrameSink {
 public:
  /// A stage in front of `next` (which must outlive it).
  /// \throws std::invalid_argument for bad parameters (validateEnvelopeFilterParams()).
  EnvelopeFilterStage(const EnvelopeFilterParams& params, FrameSink& next);
  /// Begins `next` with `meta` plus the filter's header lines (as envelopeFilter() adds them).
  void begin(const std::map<std::string, std::string>& meta,
             const std::vector<TrajectoryBody>& bodies) override;
  /// Passes the frame on with the stable poses (CausalEnvelopeFilter::push()).
  void push(const TrajectoryFrame& frame) override { next_.push(filter_->push(frame)); }
  /// Finishes `next`.
  void finish() override { next_.finish(); }

 private:
  EnvelopeFilterParams params_;
  FrameSink& next_;
  std::optional<CausalEnvelopeFilter> filter_;
};

/// The run `trajectory` envelope-filtered (\thesis{§5.5}): CausalEnvelopeFilter applied to its
/// frames in order. Frame count, frame times, body count and every non-pose column are those of
/// the input; energies and counters are kept as recorded. The header (`meta`) adds `filter`
/// (`envelope`, appended after any filter already named there with ", then"),
/// `envelope_radius` and `envelope_angle` (numbers, or the rule of the per-body default).
/// \throws std::invalid_argument for bad parameters or a frame whose pose count differs from
///         the body count.
Trajectory envelopeFilter(const Trajectory& trajectory, const EnvelopeFilterParams& params = {});

}  // namespace boxsim
