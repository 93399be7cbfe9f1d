#include "mrs_vpr/particle_evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace mrs_vpr {

EndCostTable::EndCostTable(AnchorCosts costs, const SamplingLevel& level)
    : level_(level), costs_(std::move(costs)), known_(costs_.cost.size(), 1) {}

EndCostTable::EndCostTable(LazyDifferenceMatrix& matrix, const SamplingLevel& level, std::vector<double> velocities)
    : matrix_(&matrix), level_(level), velocities_(std::move(velocities)), known_(level.grid_size, 0) {
  costs_.cost.assign(static_cast<std::size_t>(level.grid_size), std::numeric_limits<float>::infinity());
  costs_.velocity.assign(static_cast<std::size_t>(level.grid_size), 1.0F);
}

Evaluation EndCostTable::bestInWindow(int centre, int radius) {
  const int first = std::max(level_.lowest_end, centre - radius);
  const int last = std::min(level_.highest_end, centre + radius);
  // Compute the unknown ends of the window in contiguous runs.
  for (int index = first; index <= last;) {
    if (known_[static_cast<std::size_t>(index)]) {
      ++index;
      continue;
    }
    int run_end = index;
    while (run_end + 1 <= last && !known_[static_cast<std::size_t>(run_end + 1)]) ++run_end;
    computeEnds(index, run_end);
    index = run_end + 1;
  }
  Evaluation best;
  for (int index = first; index <= last; ++index) {
    const auto i = static_cast<std::size_t>(index);
    if (costs_.cost[i] < best.cost) best = {index, costs_.cost[i], costs_.velocity[i]};
  }
  return best;
}

void EndCostTable::computeEnds(int first, int last) {
  std::vector<float> sums(static_cast<std::size_t>(last - first + 1));
  std::vector<float> row(sums.size());
  for (double velocity : velocities_) {
    // Ends whose trajectory at this velocity stays inside the grid.
    const int begin = std::max(first, -static_cast<int>(std::lround(velocity * level_.k_min)));
    const int end =
        std::min(last, level_.grid_size - 1 - static_cast<int>(std::lround(velocity * level_.k_max)));
    if (begin > end) continue;
    const auto count = static_cast<std::size_t>(end - begin + 1);
    std::fill(sums.begin(), sums.begin() + static_cast<std::ptrdiff_t>(count), 0.0F);
    for (int k = level_.k_min; k <= level_.k_max; ++k) {
      // Neighbouring ends at one velocity visit neighbouring cells of a row: one contiguous request.
      const int offset = static_cast<int>(std::lround(velocity * k));
      matrix_->enhancedRow(k - level_.k_min, begin + offset, end + offset + 1, row.data());
      for (std::size_t e = 0; e < count; ++e) sums[e] += row[e];
    }
    for (std::size_t e = 0; e < count; ++e) {
      const float cost = sums[e] / static_cast<float>(level_.rows());
      const auto i = static_cast<std::size_t>(begin) + e;
      if (cost < costs_.cost[i]) {
        costs_.cost[i] = cost;
        costs_.velocity[i] = static_cast<float>(velocity);
      }
    }
  }
  std::fill(known_.begin() + first, known_.begin() + last + 1, 1);
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
