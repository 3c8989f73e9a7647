#include "boxsim/filtering/box_filter.hpp"

#include <gsl/gsl_movstat.h>
#include <gsl/gsl_vector.h>

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <string>

namespace boxsim {

namespace {

void requirePoseCounts(const TrajectoryFrame& f, std::size_t bodies) {
  if (f.x.size() != bodies || f.q.size() != bodies)
    throw std::invalid_argument("a frame at t = " + shortestText(f.t) + " s has " +
                                std::to_string(f.x.size()) + " poses for " +
                                std::to_string(bodies) +
                                " bodies; filter a trajectory as readTrajectory() returns it");
}

struct WorkspaceFree {
  void operator()(gsl_movstat_workspace* w) const { gsl_movstat_free(w); }
};

/// Centred moving mean of `values` over the workspace's ±H samples, truncated at the ends (gsl_movstat_mean).
std::vector<double> movingMean(const std::vector<double>& values,
                               gsl_movstat_workspace* workspace) {
  std::vector<double> out(values.size());
  const gsl_vector_const_view in = gsl_vector_const_view_array(values.data(), values.size());
  gsl_vector_view result = gsl_vector_view_array(out.data(), out.size());
  gsl_movstat_mean(GSL_MOVSTAT_END_TRUNCATE, &in.vector, &result.vector, workspace);
  return out;
}

}  // namespace

void validateBoxFilterParams(const BoxFilterParams& params) {
  if (params.halfWidth < 0)
    throw std::invalid_argument("box filter half width " + std::to_string(params.halfWidth) +
                                " is negative; use 0 (no filtering) or more frames, 2 as in "
                                "thesis §5.5");
}

Trajectory boxFilter(const Trajectory& trajectory, const BoxFilterParams& params) {
  validateBoxFilterParams(params);
  const std::size_t bodies = trajectory.bodies.size();
  for (const TrajectoryFrame& f : trajectory.frames) requirePoseCounts(f, bodies);

  Trajectory out = trajectory;
  const std::string previous = trajectory.meta.count("filter") ? trajectory.meta.at("filter") : "";
  out.meta["filter"] = previous.empty() ? "box" : previous + ", then box";
  out.meta["box_half_width"] = std::to_string(params.halfWidth);
  out.meta["box_orientation_average"] = orientationAverageName(params.orientationAverage);
  out.meta["box_ends"] = "truncated windows (GSL_MOVSTAT_END_TRUNCATE); energies and counters as recorded";

  const std::size_t n = trajectory.frames.size();
  const int h = params.halfWidth;
  if (n == 0 || h == 0) return out;
  const std::unique_ptr<gsl_movstat_workspace, WorkspaceFree> workspace(
      gsl_movstat_alloc2(static_cast<std::size_t>(h), static_cast<std::size_t>(h)));
  if (!workspace) throw std::runtime_error("box filter: GSL could not allocate its workspace");

  std::vector<double> series(n);
  std::vector<Quat> q(n);
  for (std::size_t b = 0; b < bodies; ++b) {
    if (trajectory.bodies[b].immovable) continue;
    // Positions: one moving mean per coordinate.
    for (int c = 0; c < 3; ++c) {
      for (std::size_t k = 0; k < n; ++k) series[k] = trajectory.frames[k].x[b][c];
      const std::vector<double> mean = movingMean(series, workspace.get());
      for (std::size_t k = 0; k < n; ++k) out.frames[k].x[b][c] = mean[k];
    }
    // Orientations: the same truncated windows, the centre frame as the sign reference.
    for (std::size_t k = 0; k < n; ++k) q[k] = trajectory.frames[k].q[b];
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t lo = k >= static_cast<std::size_t>(h) ? k - h : 0;
      const std::size_t hi = std::min(n - 1, k + static_cast<std::size_t>(h));
      out.frames[k].q[b] = averageOrientations(&q[lo], hi - lo + 1, q[k], params.orientationAverage);
    }
  }
  return out;
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
