#include "mrs_vpr/mrs/chosen_end_costs.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "mrs_vpr/contrast_enhancement.hpp"
#include "mrs_vpr/difference_matrix.hpp"

namespace mrs_vpr {

ChosenEndCosts::ChosenEndCosts(SequenceView reference, SequenceView query, const SequenceRows& rows,
                               std::vector<double> velocities, int contrast_window)
    : reference_(reference), query_(query), rows_(rows), velocities_(std::move(velocities)),
      contrast_window_(contrast_window) {
  const int length = rows_.last - rows_.first + 1;
  offsets_.assign(velocities_.size(), std::vector<int>(static_cast<std::size_t>(length)));
  lowest_.assign(static_cast<std::size_t>(length), std::numeric_limits<int>::max());
  highest_.assign(static_cast<std::size_t>(length), std::numeric_limits<int>::min());
  // One comparison a row more, so that the pieces of a row are enhanced as the whole row.
  first_differences_.assign(static_cast<std::size_t>(length), 0.0F);
  for (int r = 0; r < length && reference_.count > 0; ++r) {
    first_differences_[static_cast<std::size_t>(r)] =
        descriptorDifference(query_.frame(rows_.first + r), reference_.frame(0), reference_.descriptor_size);
  }
  for (std::size_t v = 0; v < velocities_.size(); ++v) {
    for (int r = 0; r < length; ++r) {
      // As costsByAnchor rounds them.
      const int offset = static_cast<int>(std::lround(velocities_[v] * (rows_.first + r - rows_.anchor)));
      offsets_[v][static_cast<std::size_t>(r)] = offset;
      lowest_[static_cast<std::size_t>(r)] = std::min(lowest_[static_cast<std::size_t>(r)], offset);
      highest_[static_cast<std::size_t>(r)] = std::max(highest_[static_cast<std::size_t>(r)], offset);
    }
  }
}

long long ChosenEndCosts::comparisonsPerEnd() const {
  long long cells = 0;
  for (std::size_t r = 0; r < lowest_.size(); ++r) cells += highest_[r] - lowest_[r] + 1 + 2 * (contrast_window_ / 2);
  return cells;
}

long long ChosenEndCosts::compute(int begin, int end, float* cost, float* velocity) const {
  const int columns = reference_.count;
  const int length = rows_.last - rows_.first + 1;
  const int half = contrast_window_ / 2;
  std::fill(cost, cost + (end - begin), std::numeric_limits<float>::infinity());
  std::fill(velocity, velocity + (end - begin), 0.0F);
  // Row r's enhanced cells of visited columns [visited[r], ...) from enhanced[start[r]] on.
  thread_local std::vector<float> enhanced;
  thread_local std::vector<float> raw;
  thread_local std::vector<int> visited;
  thread_local std::vector<std::size_t> start;
  visited.assign(static_cast<std::size_t>(length), 0);
  start.assign(static_cast<std::size_t>(length), 0);
  enhanced.clear();
  long long comparisons = 0;
  for (int r = 0; r < length; ++r) {
    const auto row = static_cast<std::size_t>(r);
    const int visited_begin = std::max(0, begin + lowest_[row]);
    const int visited_end = std::min(columns, end + highest_[row]);
    visited[row] = visited_begin;
    start[row] = enhanced.size();
    if (visited_begin >= visited_end) continue;  // No trajectory of these ends fits at this row.
    const int raw_begin = std::max(0, visited_begin - half);
    const int raw_end = std::min(columns, visited_end + half);
    raw.resize(static_cast<std::size_t>(raw_end - raw_begin));
    descriptorDifferences(query_.frame(rows_.first + r), reference_.frame(raw_begin), reference_.pitch(),
                          raw_end - raw_begin, reference_.descriptor_size, raw.data());
    comparisons += raw_end - raw_begin;
    enhanced.resize(start[row] + static_cast<std::size_t>(visited_end - visited_begin));
    enhanceRowSpan(raw.data(), columns, visited_begin, visited_end, contrast_window_, first_differences_[row],
                   enhanced.data() + start[row]);
  }
  const auto cell = [&](int r, int column) {
    const auto row = static_cast<std::size_t>(r);
    return enhanced[start[row] + static_cast<std::size_t>(column - visited[row])];
  };
  for (int anchor = begin; anchor < end; ++anchor) {
    float& best = cost[anchor - begin];
    for (std::size_t v = 0; v < velocities_.size(); ++v) {
      const std::vector<int>& offsets = offsets_[v];
      if (anchor + offsets.front() < 0 || anchor + offsets.back() >= columns) continue;
      // The order of sumRows in trajectory_search.cpp: four rows at a time, then the rest.
      float sum = 0.0F;
      int r = 0;
      for (; r + 3 < length; r += 4) {
        const auto o = static_cast<std::size_t>(r);
        sum += (cell(r, anchor + offsets[o]) + cell(r + 1, anchor + offsets[o + 1])) +
               (cell(r + 2, anchor + offsets[o + 2]) + cell(r + 3, anchor + offsets[o + 3]));
      }
      for (; r < length; ++r) sum += cell(r, anchor + offsets[static_cast<std::size_t>(r)]);
      const float mean = sum / static_cast<float>(length);
      if (mean < best) {
        best = mean;
        velocity[anchor - begin] = static_cast<float>(velocities_[v]);
      }
    }
  }
  return comparisons;
}

}  // namespace mrs_vpr
