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
    const double r = params.radius ? *params.radius : kEnvelopeRadiusFraction * b.halfExtents.minCoeff();
    radius_.push_back(r);
    angle_.push_back(params.angle ? *params.angle : r / b.halfExtents.norm());
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
    if ((frame.x[b] - stableX_[b]).norm() > radius_[b] ||
        rotationAngle(stableQ_[b], frame.q[b]) > angle_[b]) {
      stableX_[b] = frame.x[b];
      stableQ_[b] = frame.q[b];
    }
    display.x[b] = stableX_[b];
    display.q[b] = stableQ_[b];
  }
  return display;
}

Trajectory envelopeFilter(const Trajectory& trajectory, const EnvelopeFilterParams& params) {
  CausalEnvelopeFilter filter(trajectory.bodies, params);
  Trajectory out = trajectory;
  for (std::size_t k = 0; k < out.frames.size(); ++k) out.frames[k] = filter.push(trajectory.frames[k]);
  const std::string previous = trajectory.meta.count("filter") ? trajectory.meta.at("filter") : "";
  out.meta["filter"] = previous.empty() ? "envelope" : previous + ", then envelope";
  out.meta["envelope_radius"] =
      params.radius ? shortestText(*params.radius) + " m"
                    : shortestText(kEnvelopeRadiusFraction) + " x smallest half extent of each body (m)";
  out.meta["envelope_angle"] =
      params.angle ? shortestText(*params.angle) + " rad"
                   : "envelope radius / half diagonal of each body (rad)";
  return out;
}

}  // namespace boxsim
