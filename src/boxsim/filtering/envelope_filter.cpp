#include "boxsim/filtering/envelope_filter.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "boxsim/filtering/orientation_average.hpp"

namespace boxsim {

namespace {

void requireNonNegative(const std::optional<double>& value, const char* name, const char* unit,
                        const char* option) {
  if (value && !(std::isfinite(*value) && *value >= 0.0))
    throw std::invalid_argument(std::string("envelope ") + name + " " + shortestText(*value) +
                                " must be a finite number >= 0 " + unit + " (" + option +
                                "); leave it out for the default from the box size");
}

}  // namespace

void validateEnvelopeFilterParams(const EnvelopeFilterParams& params) {
  requireNonNegative(params.radius, "radius", "m", "--envelope-radius");
  requireNonNegative(params.angle, "angle", "rad", "--envelope-angle");
}

CausalEnvelopeFilter::CausalEnvelopeFilter(std::vector<TrajectoryBody> bodies,
                                           const EnvelopeFilterParams& params)
    : bodies_(std::move(bodies)) {
  validateEnvelopeFilterParams(params);
  for (const TrajectoryBody& b : bodies_) {
    const Envelope fallback = Envelope::of(b.halfExtents);
    const double r = params.radius ? *params.radius : fallback.radius();
    envelope_.emplace_back(r, params.angle ? *params.angle : r / b.halfExtents.norm());
  }
}

TrajectoryFrame CausalEnvelopeFilter::push(const TrajectoryFrame& frame) {
  if (frame.x.size() != bodies_.size() || frame.q.size() != bodies_.size())
    throw std::invalid_argument("a frame at t = " + shortestText(frame.t) + " s has " +
                                std::to_string(frame.x.size()) + " poses for " +
                                std::to_string(bodies_.size()) +
                                " bodies; filter a trajectory as readTrajectory() returns it");
  if (!started_) {
    stableX_ = frame.x;
    stableQ_ = frame.q;
    started_ = true;
  }
  TrajectoryFrame display = frame;
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    if (bodies_[b].immovable) continue;
    // Outside the envelope: the stable pose jumps to the simulated pose (both parts of it, so
    // the displayed pose is always a pose the simulation produced).
    if (!envelope_[b].contains(stableX_[b], stableQ_[b], frame.x[b], frame.q[b])) {
      stableX_[b] = frame.x[b];
      stableQ_[b] = frame.q[b];
    }
    display.x[b] = stableX_[b];
    display.q[b] = stableQ_[b];
  }
  return display;
}

EnvelopeFilterStage::EnvelopeFilterStage(const EnvelopeFilterParams& params, FrameSink& next)
    : params_(params), next_(next) {
  validateEnvelopeFilterParams(params_);
}

void EnvelopeFilterStage::begin(const std::map<std::string, std::string>& meta,
                                const std::vector<TrajectoryBody>& bodies) {
  filter_.emplace(bodies, params_);
  std::map<std::string, std::string> out = meta;
  const std::string previous = meta.count("filter") ? meta.at("filter") : "";
  out["filter"] = previous.empty() ? "envelope" : previous + ", then envelope";
  out["envelope_radius"] =
      params_.radius ? shortestText(*params_.radius) + " m"
                     : shortestText(kEnvelopeRadiusFraction) + " x smallest half extent of each body (m)";
  out["envelope_angle"] =
      params_.angle ? shortestText(*params_.angle) + " rad"
                    : "envelope radius / half diagonal of each body (rad)";
  next_.begin(out, bodies);
}

Trajectory envelopeFilter(const Trajectory& trajectory, const EnvelopeFilterParams& params) {
  TrajectoryCollector out;
  EnvelopeFilterStage stage(params, out);
  replayTrajectory(trajectory, stage);
  return out.take();
}

}  // namespace boxsim
