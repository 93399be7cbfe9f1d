#include "mrs_vpr/flexible_alignment.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "mrs_vpr/contrast_enhancement.hpp"
#include "mrs_vpr/difference_matrix.hpp"

namespace mrs_vpr {

int realignEnd(SequenceView reference, SequenceView query, const SequenceRows& rows, int end, double velocity,
               int slack, int contrast_window) {
  if (slack <= 0 || end < 0) return end;
  const int length = rows.last - rows.first + 1;
  const int width = 2 * slack + 1;
  const int half = contrast_window / 2;
  // Band row i covers reference columns [low[i], low[i] + width) around the straight trajectory.
  std::vector<int> low(static_cast<std::size_t>(length));
  for (int t = rows.first; t <= rows.last; ++t) {
    low[static_cast<std::size_t>(t - rows.first)] =
        end + static_cast<int>(std::lround(velocity * (t - rows.anchor))) - slack;
  }
  if (low.front() < 0 || low.back() + width > reference.count) return end;  // Near an edge of the map.

  // Enhanced differences of the band, each row from the raw differences its contrast window sees.
  std::vector<float> band(static_cast<std::size_t>(length * width));
  std::vector<float> raw;
  for (int i = 0; i < length; ++i) {
    const int begin = low[static_cast<std::size_t>(i)];
    const int raw_begin = std::max(0, begin - half);
    const int raw_end = std::min(reference.count, begin + width + half);
    raw.resize(static_cast<std::size_t>(raw_end - raw_begin));
    descriptorDifferences(query.frame(rows.first + i), reference.frame(raw_begin), reference.pitch(),
                          raw_end - raw_begin, query.descriptor_size, raw.data());
    const float first_difference =
        descriptorDifference(query.frame(rows.first + i), reference.frame(0), query.descriptor_size);
    enhanceRowSpan(raw.data(), reference.count, begin, begin + width, contrast_window, first_difference,
                   band.data() + static_cast<std::ptrdiff_t>(i) * width);
  }

  // Lowest path cost to each band cell, and the column it came from.
  constexpr float kInfinity = std::numeric_limits<float>::infinity();
  std::vector<float> cost(band.begin(), band.begin() + width);
  std::vector<int> from(static_cast<std::size_t>(length * width), -1);
  std::vector<float> next(static_cast<std::size_t>(width));
  for (int i = 1; i < length; ++i) {
    const int shift = low[static_cast<std::size_t>(i)] - low[static_cast<std::size_t>(i - 1)];
    for (int k = 0; k < width; ++k) {
      float best = kInfinity;
      int best_column = -1;
      for (int step = 0; step <= 2; ++step) {
        const int previous = k + shift - step;  // Band index of column c - step in the row before.
        if (previous < 0 || previous >= width) continue;
        const float candidate = cost[static_cast<std::size_t>(previous)] + (step == 1 ? 0.0F : kStepPenalty);
        if (candidate < best) {
          best = candidate;
          best_column = previous;
        }
      }
      next[static_cast<std::size_t>(k)] = best + band[static_cast<std::size_t>(i * width + k)];
      from[static_cast<std::size_t>(i * width + k)] = best_column;
    }
    cost.swap(next);
  }
  int k = static_cast<int>(std::min_element(cost.begin(), cost.end()) - cost.begin());
  if (!std::isfinite(cost[static_cast<std::size_t>(k)])) return end;
  // Back from the newest row to the anchor's.
  for (int i = length - 1; i > rows.anchor - rows.first; --i) {
    k = from[static_cast<std::size_t>(i * width + k)];
    if (k < 0) return end;
  }
  return low[static_cast<std::size_t>(rows.anchor - rows.first)] + k;
}

}  // namespace mrs_vpr
