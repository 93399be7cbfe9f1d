#include "mrs_vpr/particle_evaluation.hpp"

#include <algorithm>
#include <cmath>

namespace mrs_vpr {

Evaluation bestInWindow(const AnchorCosts& costs, int centre, int radius, const SamplingLevel& level) {
  Evaluation best;
  const int begin = std::max(level.lowest_end, centre - radius);
  const int end = std::min(level.highest_end, centre + radius);
  for (int index = begin; index <= end; ++index) {
    const auto i = static_cast<std::size_t>(index);
    if (costs.cost[i] < best.cost) best = {index, costs.cost[i], costs.velocity[i]};
  }
  return best;
}

Evaluation evaluateTrajectories(LazyDifferenceMatrix& matrix, const SamplingLevel& level, int centre, int radius,
                                const std::vector<double>& velocities) {
  Evaluation best;
  const int first_end = std::max(level.lowest_end, centre - radius);
  const int last_end = std::min(level.highest_end, centre + radius);
  if (first_end > last_end) return best;
  std::vector<float> sums(static_cast<std::size_t>(last_end - first_end + 1));
  std::vector<float> row(sums.size());
  for (double velocity : velocities) {
    // Ends whose trajectory at this velocity stays inside the grid.
    const int begin = std::max(first_end, -static_cast<int>(std::lround(velocity * level.k_min)));
    const int end =
        std::min(last_end, level.grid_size - 1 - static_cast<int>(std::lround(velocity * level.k_max)));
    if (begin > end) continue;
    const auto count = static_cast<std::size_t>(end - begin + 1);
    std::fill(sums.begin(), sums.begin() + static_cast<std::ptrdiff_t>(count), 0.0F);
    for (int k = level.k_min; k <= level.k_max; ++k) {
      // Neighbouring ends at one velocity visit neighbouring cells of a row: one contiguous request.
      const int offset = static_cast<int>(std::lround(velocity * k));
      matrix.enhancedRow(k - level.k_min, begin + offset, end + offset + 1, row.data());
      for (std::size_t e = 0; e < count; ++e) sums[e] += row[e];
    }
    for (std::size_t e = 0; e < count; ++e) {
      const float cost = sums[e] / static_cast<float>(level.rows());
      if (cost < best.cost) best = {begin + static_cast<int>(e), cost, static_cast<float>(velocity)};
    }
  }
  return best;
}

std::vector<double> velocitiesNear(const std::vector<double>& all, double centre, double spread) {
  std::vector<double> near;
  for (double velocity : all) {
    if (std::abs(velocity - centre) <= spread + 1e-9) near.push_back(velocity);
  }
  if (near.empty() && !all.empty()) {
    near.push_back(*std::min_element(all.begin(), all.end(), [centre](double a, double b) {
      return std::abs(a - centre) < std::abs(b - centre);
    }));
  }
  return near;
}

}  // namespace mrs_vpr
