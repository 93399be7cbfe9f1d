#include "mrs_vpr/acceptance.hpp"

#include <algorithm>
#include <cmath>

namespace mrs_vpr {
namespace {

float medianOf(std::vector<float>& values) {
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace

float costSpread(const std::vector<float>& costs) {
  const std::size_t step = std::max<std::size_t>(1, costs.size() / kSpreadSamples);
  std::vector<float> samples;
  samples.reserve(std::min(costs.size(), static_cast<std::size_t>(kSpreadSamples) + 1));
  for (std::size_t i = 0; i < costs.size(); i += step) {
    if (std::isfinite(costs[i])) samples.push_back(costs[i]);
  }
  if (samples.size() < 3) return 0.0F;
  const float centre = medianOf(samples);
  for (float& value : samples) value = std::abs(value - centre);
  // 1.4826 MAD is the standard deviation of a Gaussian.
  return 1.4826F * medianOf(samples);
}

float distinctiveness(float best, float runner_up, float spread, int rivals) {
  if (!std::isfinite(best) || !std::isfinite(runner_up) || !(spread > 0.0F) || rivals < kMinRivalEnds) return 0.0F;
  return std::max(0.0F, (runner_up - best) / spread);
}

void applyAcceptance(Match& match, double threshold) {
  match.accepted = match.reference_index >= 0 && match.confidence >= threshold;
}

}  // namespace mrs_vpr
