#include "boxsim/filtering/box_filter.hpp"

#include <gsl/gsl_movstat.h>

#include <algorithm>
#include <memory>
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
  meta["box_ends"] = "truncated windows (GSL_MOVSTAT_END_TRUNCATE); energies and counters as recorded";
  return meta;
}

}  // namespace

/// GSL's moving-mean accumulators, one per coordinate of every movable body, each in a
/// workspace of its own (gsl_movstat_alloc_with_size() sizes the accumulator's state).
struct BoxFilterStage::Accumulators {
  /// Frees a GSL workspace. A member, not in the file's anonymous namespace: a type of
  /// internal linkage in a field of this externally visible class would draw
  /// -Wsubobject-linkage.
  struct WorkspaceFree {
    void operator()(gsl_movstat_workspace* w) const { gsl_movstat_free(w); }
  };
  std::vector<std::unique_ptr<gsl_movstat_workspace, WorkspaceFree>> workspaces;

  Accumulators(std::size_t count, std::size_t h) {
    const gsl_movstat_accum* mean = gsl_movstat_accum_mean;
    for (std::size_t i = 0; i < count; ++i) {
      workspaces.emplace_back(gsl_movstat_alloc_with_size(mean->size(2 * h + 1), h, h));
      gsl_movstat_workspace* w = workspaces.back().get();
      if (w == nullptr) throw std::runtime_error("box filter: GSL could not allocate its workspace");
      mean->init(w->K, w->state);
    }
  }
  void insert(std::size_t i, double x) { gsl_movstat_accum_mean->insert(x, workspaces[i]->state); }
  void deleteOldest(std::size_t i) { gsl_movstat_accum_mean->delete_oldest(workspaces[i]->state); }
  double get(std::size_t i) const {
    double result = 0.0;
    gsl_movstat_accum_mean->get(nullptr, &result, workspaces[i]->state);
    return result;
  }
};

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

BoxFilterStage::~BoxFilterStage() = default;

void BoxFilterStage::begin(const std::map<std::string, std::string>& meta,
                           const std::vector<TrajectoryBody>& bodies) {
  bodies_ = bodies;
  const std::size_t movable = static_cast<std::size_t>(
      std::count_if(bodies.begin(), bodies.end(), [](const TrajectoryBody& b) { return !b.immovable; }));
  if (params_.halfWidth > 0)
    means_ = std::make_unique<Accumulators>(3 * movable, static_cast<std::size_t>(params_.halfWidth));
  next_.begin(boxFilterMeta(meta, params_), bodies);
}

void BoxFilterStage::push(const TrajectoryFrame& frame) {
  requirePoseCounts(frame, bodies_.size());
  const long h = params_.halfWidth;
  if (h == 0) {
    next_.push(frame);
    return;
  }
  // gsl_movstat_apply_accum's main loop: insert sample i, then read the mean of sample i − H.
  std::size_t a = 0;
  for (std::size_t b = 0; b < bodies_.size(); ++b)
    if (!bodies_[b].immovable)
      for (int c = 0; c < 3; ++c) means_->insert(a++, frame.x[b][c]);
  window_.push_back(frame);
  if (window_.size() > static_cast<std::size_t>(2 * h + 1)) window_.pop_front();
  ++received_;
  if (received_ > h) emit(received_ - 1 - h);
}

void BoxFilterStage::finish() {
  const long h = params_.halfWidth;
  // gsl_movstat_apply_accum's end for GSL_MOVSTAT_END_TRUNCATE: the windows of the last H
  // samples shrink, losing their oldest sample while it lies more than H before them.
  for (long k = std::max(received_ - h, 0L); h > 0 && k < received_; ++k) {
    if (k - h > 0)
      for (std::size_t a = 0; a < means_->workspaces.size(); ++a) means_->deleteOldest(a);
    emit(k);
  }
  next_.finish();
}

void BoxFilterStage::emit(long k) {
  const long h = params_.halfWidth;
  const long first = received_ - static_cast<long>(window_.size());  // frame index of window_[0]
  const long lo = std::max(k - h, 0L);
  const long hi = std::min(k + h, received_ - 1);
  TrajectoryFrame out = window_[static_cast<std::size_t>(k - first)];
  std::vector<Quat> q(static_cast<std::size_t>(hi - lo + 1));
  std::size_t a = 0;
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    if (bodies_[b].immovable) continue;
    for (int c = 0; c < 3; ++c) out.x[b][c] = means_->get(a++);
    for (long j = lo; j <= hi; ++j)
      q[static_cast<std::size_t>(j - lo)] = window_[static_cast<std::size_t>(j - first)].q[b];
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
  std::vector<Quat> q(s);
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    if (bodies_[b].immovable) continue;
    Vec3 sum = Vec3::Zero();
    for (std::size_t i = 0; i < s; ++i) {
      sum += window_[i].x[b];
      q[i] = window_[i].q[b];
    }
    display.x[b] = sum / static_cast<double>(s);
    display.q[b] = averageOrientations(q.data(), s, q[reference], params_.orientationAverage);
  }
  return display;
}

}  // namespace boxsim
