/// \file
/// A filter of \thesis{§5.5} chosen by name, as the command line (`boxsim run --filter`,
/// `boxsim filter`) names it, with its parameters checked together.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "boxsim/core/frame_sink.hpp"

namespace boxsim {

/// Which filter to apply to a recorded run, and the parameters given for it (empty ones take
/// the filter's defaults).
struct FilterChoice {
  std::string name;               ///< "box", "envelope", or empty for none
  std::optional<int> halfWidth;   ///< box filter: BoxFilterParams::halfWidth, frames
  std::optional<double> radius;   ///< envelope filter: EnvelopeFilterParams::radius, m
  std::optional<double> angle;    ///< envelope filter: EnvelopeFilterParams::angle, rad
};

/// Checks a choice before a run starts, so a long simulation does not end in a refused filter.
/// \throws std::invalid_argument naming the problem and the fix: an unknown filter name, a
///         parameter the chosen filter does not take (a half width for the envelope filter, a
///         radius or an angle for the box filter, any of them with no filter), or a value out
///         of range (validateBoxFilterParams(), validateEnvelopeFilterParams()).
void validateFilterChoice(const FilterChoice& choice);

/// The trajectory filtered as `choice` says (boxFilter() or envelopeFilter(), which name the
/// filter and its parameters in the header); an empty name returns it unchanged.
/// \throws std::invalid_argument as validateFilterChoice(), and as the filter does.
Trajectory applyFilter(const Trajectory& trajectory, const FilterChoice& choice);

/// The filter `choice` names as a stage in front of `next` (BoxFilterStage or
/// EnvelopeFilterStage), for a run streamed frame by frame; an empty name returns nullptr (the
/// frames go to `next` unfiltered).
/// \throws std::invalid_argument as validateFilterChoice().
std::unique_ptr<FrameSink> makeFilterStage(const FilterChoice& choice, FrameSink& next);

}  // namespace boxsim
