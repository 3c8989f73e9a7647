#include "boxsim/filtering/box_filter.hpp"

#include <algorithm>
#include <deque>
#include <stdexcept>
#include <string>
#include <utility>

namespace boxsim {

namespace {

void requirePoseCounts(const TrajectoryFrame& f, std::size_t bodies) {
  if (f.x.size() != bodies || f.q.size() != bodies)
    throw std::invalid_argument("a frame at t = " + shortestText(f.t) + " s has " +
                                std::to_string(f.x.size()) + " poses for " +
                                std::to_string(bodies) +
                                " bodies; filter a trajectory as readTrajectory() returns it");
}

/// The header lines boxFilter() adds to a run's.
std::map<std::string, std::string> boxFilterMeta(std::map<std::string, std::string> meta,
                                                 const BoxFilterParams& params) {
  const std::string previous = meta.count("filter") ? meta.at("filter") : "";
  meta["filter"] = previous.empty() ? "box" : previous + ", then box";
  meta["box_half_width"] = std::to_string(params.halfWidth);
  meta["box_orientation_average"] = orientationAverageName(params.orientationAverage);
  meta["box_ends"] = "truncated windows; energies and counters as recorded";
  return meta;
}

/// The mean position of body `b` over the frames window[from] … window[to] (a sum in frame
/// order, then one division), and their orientations in `q`, for averageOrientations(). Every
/// form of the box filter averages through it, so they agree bit for bit.
Vec3 windowMean(const std::deque<TrajectoryFrame>& window, std::size_t from, std::size_t to,
                std::size_t b, std::vector<Quat>& q) {
  q.resize(to - from + 1);
  Vec3 sum = Vec3::Zero();
  for (std::size_t i = from; i <= to; ++i) {
    sum += window[i].x[b];
    q[i - from] = window[i].q[b];
  }
  return sum / static_cast<double>(to - from + 1);
}

}  // namespace

void validateBoxFilterParams(const BoxFilterParams& params) {
  if (params.halfWidth < 0)
    throw std::invalid_argument("box filter half width " + std::to_string(params.halfWidth) +
                                " is negative; use 0 (no filtering) or more frames, 2 as in "
                                "thesis §5.5");
}

Trajectory boxFilter(const Trajectory& trajectory, const BoxFilterParams& params) {
  TrajectoryCollector out;
  BoxFilterStage stage(params, out);
  replayTrajectory(trajectory, stage);
  return out.take();
}

BoxFilterStage::BoxFilterStage(const BoxFilterParams& params, FrameSink& next)
    : params_(params), next_(next) {
  validateBoxFilterParams(params_);
}

void BoxFilterStage::begin(const std::map<std::string, std::string>& meta,
                           const std::vector<TrajectoryBody>& bodies) {
  bodies_ = bodies;
  next_.begin(boxFilterMeta(meta, params_), bodies);
}

void BoxFilterStage::push(const TrajectoryFrame& frame) {
  requirePoseCounts(frame, bodies_.size());
  const long h = params_.halfWidth;
  if (h == 0) {
    next_.push(frame);
    return;
  }
  // Frame k − H is complete once frame k is in.
  window_.push_back(frame);
  if (window_.size() > static_cast<std::size_t>(2 * h + 1)) window_.pop_front();
  ++received_;
  if (received_ > h) emit(received_ - 1 - h);
}

void BoxFilterStage::finish() {
  const long h = params_.halfWidth;
  // The last H frames: their windows are truncated at the end of the run.
  for (long k = std::max(received_ - h, 0L); h > 0 && k < received_; ++k) emit(k);
  next_.finish();
}

void BoxFilterStage::emit(long k) {
  const long h = params_.halfWidth;
  const long first = received_ - static_cast<long>(window_.size());  // frame index of window_[0]
  const auto lo = static_cast<std::size_t>(std::max(k - h, 0L) - first);
  const auto hi = static_cast<std::size_t>(std::min(k + h, received_ - 1) - first);
  TrajectoryFrame out = window_[static_cast<std::size_t>(k - first)];
  std::vector<Quat> q;
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    if (bodies_[b].immovable) continue;
    out.x[b] = windowMean(window_, lo, hi, b, q);
    // The centre frame is the sign reference, as in boxFilter().
    out.q[b] = averageOrientations(q.data(), q.size(), out.q[b], params_.orientationAverage);
  }
  next_.push(out);
}

CausalBoxFilter::CausalBoxFilter(std::vector<TrajectoryBody> bodies, const BoxFilterParams& params)
    : bodies_(std::move(bodies)), params_(params) {
  validateBoxFilterParams(params_);
}

TrajectoryFrame CausalBoxFilter::push(const TrajectoryFrame& newest) {
  requirePoseCounts(newest, bodies_.size());
  window_.push_back(newest);
  const std::size_t capacity = 2 * static_cast<std::size_t>(params_.halfWidth) + 1;
  if (window_.size() > capacity) window_.pop_front();
  const std::size_t s = window_.size();
  // The sign reference: frame k − H, the centre of a full window (frame 0 while k < H).
  const std::size_t h = static_cast<std::size_t>(params_.halfWidth);
  const std::size_t reference = s - 1 >= h ? s - 1 - h : 0;

  TrajectoryFrame display = newest;
  std::vector<Quat> q;
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    if (bodies_[b].immovable) continue;
    display.x[b] = windowMean(window_, 0, s - 1, b, q);
    display.q[b] = averageOrientations(q.data(), s, q[reference], params_.orientationAverage);
  }
  return display;
}

}  // namespace boxsim
