#pragma once

#include <algorithm>
#include <limits>
#include <vector>

namespace mrs_vpr {
namespace node {

/// Continuous mode's questions of one period take at most this share of it (by the last one's time);
/// beyond, it localises fewer of the keyframes that came, evenly spread.
constexpr double kContinuousShare = 0.2;

/// How many questions fit in kContinuousShare of a period of `period_s` when the last one took
/// `last_query_ms` (1 before any was timed).
inline int affordableQueries(double period_s, double last_query_ms) {
  if (last_query_ms <= 0.0) return 1;
  // Bounded before the conversion: a long period and a quick question exceed an int.
  return static_cast<int>(std::min(kContinuousShare * period_s * 1000.0 / last_query_ms,
                                   static_cast<double>(std::numeric_limits<int>::max())));
}

/**
 * The test sequences continuous mode asks about in one period, each given by the map's frame count
 * at its end (a sequence ending there holds the `length` frames before it).
 *
 * Every keyframe that came since the last question ends one, oldest first, so that each keyframe is
 * localised once: at the default centred alignment a question localises the keyframe half a sequence
 * back, and asking about the newest only would leave the keyframes between two periods unasked. At
 * most `affordable` of them (what the period's budget allows), evenly spread and always with the
 * newest. The first question (`previous_size` 0) and the first after the map shrank (a reset, a
 * smaller map loaded) ask about the newest only. `first_size`: the fewest frames a question needs.
 * No ROS inside.
 */
inline std::vector<int> continuousQueryEnds(int previous_size, int size, int first_size, int affordable) {
  if (size < first_size) return {};
  if (previous_size <= 0 || size < previous_size) return {size};
  const int oldest = std::max(previous_size + 1, first_size);
  const int fresh = size - oldest + 1;
  if (fresh <= 0) return {};  // nothing newer (a full map, a map of the same size reloaded)
  const int queries = std::min(fresh, std::max(affordable, 1));
  std::vector<int> ends;
  for (int q = queries - 1; q >= 0; --q) {
    ends.push_back(size - static_cast<int>(static_cast<long long>(q) * fresh / queries));
  }
  return ends;
}

}  // namespace node
}  // namespace mrs_vpr
