#include "mrs_vpr/mrs/particle_evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace mrs_vpr {

EndCostTable::EndCostTable(AnchorCosts costs, const SamplingLevel& level)
    : level_(level), costs_(std::move(costs)), known_(costs_.cost.size(), 1) {}

EndCostTable::EndCostTable(LazyDifferenceMatrix& matrix, const SamplingLevel& level, std::vector<double> velocities,
                           bool look_ahead)
    : matrix_(&matrix), level_(level), velocities_(std::move(velocities)), known_(level.grid_size, 0),
      look_ahead_(look_ahead) {
  costs_.cost.assign(static_cast<std::size_t>(level.grid_size), std::numeric_limits<float>::infinity());
  costs_.velocity.assign(static_cast<std::size_t>(level.grid_size), 1.0F);
  // Row r of the trajectory of velocity v through end J is the cell J + round(v * (k_min + r)).
  for (double velocity : velocities_) {
    std::vector<int>& offsets = offsets_.emplace_back();
    for (int k = level.k_min; k <= level.k_max; ++k) offsets.push_back(static_cast<int>(std::lround(velocity * k)));
  }
}

Evaluation EndCostTable::bestInWindow(int centre, int radius) {
  const int first = std::max(level_.lowest_end, centre - radius);
  const int last = std::min(level_.highest_end, centre + radius);
  // Compute the unknown ends of the window in contiguous runs; looking ahead, reach a radius further
  // where they are unknown too: a particle moves at most `radius` a step.
  const int reach = look_ahead_ ? radius : 0;
  const int pad_first = std::max(level_.lowest_end, first - reach);
  const int pad_last = std::min(level_.highest_end, last + reach);
  for (int index = first; index <= last;) {
    if (known_[static_cast<std::size_t>(index)]) {
      ++index;
      continue;
    }
    int run_begin = index;
    while (run_begin - 1 >= pad_first && !known_[static_cast<std::size_t>(run_begin - 1)]) --run_begin;
    int run_end = index;
    while (run_end + 1 <= pad_last && !known_[static_cast<std::size_t>(run_end + 1)]) ++run_end;
    computeEnds(run_begin, run_end);
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
  std::fill(known_.begin() + first, known_.begin() + last + 1, 1);
  // The velocities with ends in [first, last] whose trajectory stays inside the grid.
  struct Fan {
    std::size_t velocity;
    int begin;
    int end;
  };
  std::vector<Fan> fans;
  for (std::size_t v = 0; v < velocities_.size(); ++v) {
    const int begin = std::max(first, -offsets_[v].front());
    const int end = std::min(last, level_.grid_size - 1 - offsets_[v].back());
    if (begin <= end) fans.push_back({v, begin, end});
  }
  if (fans.empty()) return;  // No trajectory through these ends fits.
  const auto span = static_cast<std::size_t>(last - first + 1);
  // Each row's fans lie in one short span of cells: one request per row, all served first (by
  // several threads where the matrix allows), then summed row by row in order.
  const auto rows = static_cast<std::size_t>(level_.rows());
  std::vector<LazyDifferenceMatrix::RowRequest> requests(rows);
  std::vector<std::size_t> starts(rows + 1, 0);  // Where each row's values begin in `values`.
  for (std::size_t r = 0; r < rows; ++r) {
    int low = level_.grid_size;
    int high = 0;
    for (const Fan& fan : fans) {
      const int offset = offsets_[fan.velocity][r];
      low = std::min(low, fan.begin + offset);
      high = std::max(high, fan.end + offset + 1);
    }
    requests[r] = {static_cast<int>(r), low, high, nullptr};
    starts[r + 1] = starts[r] + static_cast<std::size_t>(high - low);
  }
  std::vector<float> values(starts.back());
  for (std::size_t r = 0; r < rows; ++r) requests[r].out = values.data() + starts[r];
  matrix_->enhancedRows(requests);
  std::vector<float> sums(fans.size() * span, 0.0F);
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t f = 0; f < fans.size(); ++f) {
      const int offset = offsets_[fans[f].velocity][r];
      const float* row_values = requests[r].out + (fans[f].begin + offset - requests[r].begin);
      float* fan_sums = sums.data() + f * span;
      const int count = fans[f].end - fans[f].begin + 1;
      for (int e = 0; e < count; ++e) fan_sums[e] += row_values[e];
    }
  }
  for (std::size_t f = 0; f < fans.size(); ++f) {
    for (int index = fans[f].begin; index <= fans[f].end; ++index) {
      const float sum = sums[f * span + static_cast<std::size_t>(index - fans[f].begin)];
      const float cost = sum / static_cast<float>(level_.rows());
      const auto i = static_cast<std::size_t>(index);
      if (cost < costs_.cost[i]) {
        costs_.cost[i] = cost;
        costs_.velocity[i] = static_cast<float>(velocities_[fans[f].velocity]);
      }
    }
  }
}

double fanSpread(double velocity_step, int previous_rows, bool after_coarsest) {
  const double grid_steps = after_coarsest ? 2.0 : 1.0;
  return std::max(grid_steps * velocity_step, 2.0 / previous_rows);
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
