#include "boxsim/filtering/filter_choice.hpp"

#include <stdexcept>

#include "boxsim/filtering/box_filter.hpp"
#include "boxsim/filtering/envelope_filter.hpp"

namespace boxsim {

namespace {

BoxFilterParams boxParams(const FilterChoice& choice) {
  BoxFilterParams p;
  if (choice.halfWidth) p.halfWidth = *choice.halfWidth;
  return p;
}

EnvelopeFilterParams envelopeParams(const FilterChoice& choice) {
  return EnvelopeFilterParams{choice.radius, choice.angle};
}

}  // namespace

void validateFilterChoice(const FilterChoice& choice) {
  const bool envelopeOptions = choice.radius || choice.angle;
  if (choice.name.empty()) {
    if (choice.halfWidth || envelopeOptions)
      throw std::invalid_argument(
          "--filter-half-width, --envelope-radius and --envelope-angle need a filter; add "
          "--filter box or --filter envelope");
    return;
  }
  if (choice.name == "box") {
    if (envelopeOptions)
      throw std::invalid_argument(
          "the box filter takes no --envelope-radius or --envelope-angle; use "
          "--filter-half-width, or --filter envelope");
    validateBoxFilterParams(boxParams(choice));
  } else if (choice.name == "envelope") {
    if (choice.halfWidth)
      throw std::invalid_argument(
          "the envelope filter takes no --filter-half-width; use --envelope-radius and "
          "--envelope-angle, or --filter box");
    validateEnvelopeFilterParams(envelopeParams(choice));
  } else {
    throw std::invalid_argument("unknown filter '" + choice.name + "'; use box or envelope");
  }
}

Trajectory applyFilter(const Trajectory& trajectory, const FilterChoice& choice) {
  validateFilterChoice(choice);
  if (choice.name == "box") return boxFilter(trajectory, boxParams(choice));
  if (choice.name == "envelope") return envelopeFilter(trajectory, envelopeParams(choice));
  return trajectory;
}

std::unique_ptr<FrameSink> makeFilterStage(const FilterChoice& choice, FrameSink& next) {
  validateFilterChoice(choice);
  if (choice.name == "box") return std::make_unique<BoxFilterStage>(boxParams(choice), next);
  if (choice.name == "envelope")
    return std::make_unique<EnvelopeFilterStage>(envelopeParams(choice), next);
  return nullptr;
}

}  // namespace boxsim
