#include "mrs_vpr/trajectory_search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "mrs_vpr/acceptance.hpp"
#include "simd/vector_kernel.hpp"

namespace mrs_vpr {
namespace {

/// sum[i] = rows[0][i] + ... + rows[count - 1][i] for i < width: the cells of `width` neighbouring
/// trajectories, row by row. Four rows at a time, so that the inner loop is a contiguous,
/// vectorisable add that loads and stores the sums a quarter as often.
MRS_VPR_VECTOR_KERNEL
void sumRows(const float* const* rows, int count, int width, float* __restrict sum) {
  std::fill(sum, sum + width, 0.0F);
  int r = 0;
  for (; r + 3 < count; r += 4) {
    const float* __restrict r0 = rows[r];
    const float* __restrict r1 = rows[r + 1];
    const float* __restrict r2 = rows[r + 2];
    const float* __restrict r3 = rows[r + 3];
    for (int i = 0; i < width; ++i) sum[i] += (r0[i] + r1[i]) + (r2[i] + r3[i]);
  }
  for (; r < count; ++r) {
    const float* __restrict row = rows[r];
    for (int i = 0; i < width; ++i) sum[i] += row[i];
  }
}

/// Where the mean sum[i] / length is lower than cost[i], it and `velocity` replace it.
MRS_VPR_VECTOR_KERNEL
void keepLowerMeans(const float* __restrict sum, int width, float length, float velocity, float* __restrict cost,
                    float* __restrict best_velocity) {
  for (int i = 0; i < width; ++i) {
    const float mean = sum[i] / length;
    const bool lower = mean < cost[i];
    cost[i] = lower ? mean : cost[i];
    best_velocity[i] = lower ? velocity : best_velocity[i];
  }
}

/// The lowest of `count` costs from `costs` (infinity when count is 0). Eight running minima: a single
/// one would wait on itself at every cost, and a map-sized table is scored on every query.
float lowestCost(const float* costs, int count) {
  constexpr int kChains = 8;
  float lowest[kChains];
  std::fill(lowest, lowest + kChains, std::numeric_limits<float>::infinity());
  int i = 0;
  for (; i + kChains <= count; i += kChains) {
    for (int k = 0; k < kChains; ++k) lowest[k] = std::min(lowest[k], costs[i + k]);
  }
  for (; i < count; ++i) lowest[0] = std::min(lowest[0], costs[i]);
  return *std::min_element(lowest, lowest + kChains);
}

/// How many of `count` costs are finite (a trajectory fits their end).
MRS_VPR_VECTOR_KERNEL
int finiteCosts(const float* __restrict costs, int count) {
  int finite = 0;
  for (int i = 0; i < count; ++i) finite += std::abs(costs[i]) < std::numeric_limits<float>::infinity() ? 1 : 0;
  return finite;
}

}  // namespace

std::vector<double> velocities(const SequenceParams& params) {
  std::vector<double> result;
  const int count = static_cast<int>(params.velocityCount());  // Validated: at most kMaxVelocities.
  for (int i = 0; i < count; ++i) {
    result.push_back(params.velocity_min + i * params.velocity_step);
  }
  return result;
}

SequenceRows sequenceRowsFor(int frame, const SequenceParams& params) {
  SequenceRows rows;
  rows.anchor = frame;
  if (params.alignment == WindowAlignment::kCausal) {
    rows.last = frame;
    rows.first = frame - params.sequence_length + 1;
  } else {
    rows.first = frame - params.sequence_length / 2;
    rows.last = rows.first + params.sequence_length - 1;
  }
  return rows;
}

SequenceRows wholeSequenceRows(int count, WindowAlignment alignment) {
  SequenceRows rows;
  rows.first = 0;
  rows.last = count - 1;
  rows.anchor = alignment == WindowAlignment::kCausal ? rows.last : count / 2;
  return rows;
}

std::vector<FrameRange> ownPlaceEnds(int winner, int exclusion, int columns, const PlaceLinks* links,
                                     int frames_per_end) {
  const int half = exclusion / 2;
  std::vector<FrameRange> own{{std::max(0, winner - half), std::min(columns, winner + half + 1)}};
  if (links == nullptr) return own;
  for (const FrameRange& frames : links->samePlaceAs(winner * frames_per_end, half * frames_per_end)) {
    // End J of a pooled table is the cell ending at frame J * frames_per_end.
    const FrameRange ends{(frames.begin + frames_per_end - 1) / frames_per_end,
                          std::min(columns, (frames.end + frames_per_end - 1) / frames_per_end)};
    if (ends.begin < ends.end) own.push_back(ends);
  }
  return mergedRanges(std::move(own));
}

Rivals rivalsOutside(const std::vector<float>& cost_by_anchor, const std::vector<FrameRange>& own) {
  Rivals rivals{std::numeric_limits<float>::infinity(), 0};
  const float* costs = cost_by_anchor.data();
  int begin = 0;
  const auto gap = [&](int end) {
    if (end <= begin) return;
    rivals.lowest = std::min(rivals.lowest, lowestCost(costs + begin, end - begin));
    rivals.finite += finiteCosts(costs + begin, end - begin);
  };
  for (const FrameRange& range : own) {
    gap(range.begin);
    begin = std::max(begin, range.end);
  }
  gap(static_cast<int>(cost_by_anchor.size()));
  return rivals;
}

Match scoreAround(const std::vector<float>& cost_by_anchor, int winner, int exclusion, const PlaceLinks* links,
                  int frames_per_end) {
  Match match;
  const int columns = static_cast<int>(cost_by_anchor.size());
  if (winner < 0 || winner >= columns) return match;
  const int half = exclusion / 2;
  // The ends within half of the winner are its own; so are its place's on other visits. All others are rivals.
  const int near_begin = std::max(0, winner - half);
  const int near_end = std::min(columns, winner + half + 1);
  const float best = lowestCost(cost_by_anchor.data() + near_begin, near_end - near_begin);
  const Rivals rivals =
      rivalsOutside(cost_by_anchor, ownPlaceEnds(winner, exclusion, columns, links, frames_per_end));
  const float runner_up = rivals.lowest;
  match.reference_index = winner;
  match.sequence_difference = best;
  // Without a distinct runner-up there is nothing to be sure about: score 1, confidence 0.
  match.score = (std::isfinite(best) && std::isfinite(runner_up) && runner_up > 0.0F)
                    ? std::clamp(best / runner_up, 0.0F, 1.0F)
                    : 1.0F;
  match.rivals = rivals.finite;
  match.rival_places = placesAmong(rivals.finite, 1, exclusion);
  match.confidence = distinctiveness(best, runner_up, costSpread(cost_by_anchor), rivals.finite);
  return match;
}

Match scoreFromCosts(const std::vector<float>& cost_by_anchor, int exclusion, const PlaceLinks* links) {
  const float lowest = lowestCost(cost_by_anchor.data(), static_cast<int>(cost_by_anchor.size()));
  if (!std::isfinite(lowest)) return Match{};  // No trajectory fits.
  // The first end at the lowest cost, as a scan from the start would pick.
  const auto best = std::find(cost_by_anchor.begin(), cost_by_anchor.end(), lowest);
  return scoreAround(cost_by_anchor, static_cast<int>(best - cost_by_anchor.begin()), exclusion, links);
}

Match scoreAnchorCosts(const AnchorCosts& costs, int exclusion, const PlaceLinks* links) {
  Match match = scoreFromCosts(costs.cost, exclusion, links);
  if (match.reference_index >= 0) match.velocity = costs.velocity[static_cast<std::size_t>(match.reference_index)];
  return match;
}

std::vector<int> distinctMinima(const std::vector<float>& cost_by_anchor, int separation, int count) {
  std::vector<std::pair<float, int>> heap;
  for (std::size_t j = 0; j < cost_by_anchor.size(); ++j) {
    if (std::isfinite(cost_by_anchor[j])) heap.emplace_back(cost_by_anchor[j], static_cast<int>(j));
  }
  // A min-heap: popping costs O(log n) per end, and each chosen end suppresses at most
  // 2 * separation + 1 others, so few are popped whatever the size of the table.
  const auto greater = [](const std::pair<float, int>& a, const std::pair<float, int>& b) { return a > b; };
  std::make_heap(heap.begin(), heap.end(), greater);
  std::vector<int> chosen;
  while (!heap.empty() && static_cast<int>(chosen.size()) < count) {
    std::pop_heap(heap.begin(), heap.end(), greater);
    const int index = heap.back().second;
    heap.pop_back();
    const bool near_chosen = std::any_of(chosen.begin(), chosen.end(),
                                         [&](int other) { return std::abs(other - index) <= separation; });
    if (!near_chosen) chosen.push_back(index);
  }
  return chosen;
}

AnchorCosts costsByAnchor(const cv::Mat& enhanced, const SequenceRows& rows, const std::vector<double>& velocities,
                          const QueryStop* stop) {
  CV_Assert(enhanced.type() == CV_32FC1);
  std::vector<const float*> row_data(static_cast<std::size_t>(enhanced.rows));
  for (int t = 0; t < enhanced.rows; ++t) row_data[static_cast<std::size_t>(t)] = enhanced.ptr<float>(t);
  AnchorCosts costs;
  costsByAnchor(row_data, enhanced.cols, rows, velocities, costs, stop);
  return costs;
}

void costsByAnchor(const std::vector<const float*>& enhanced_rows, int columns, const SequenceRows& rows,
                   const std::vector<double>& velocities, AnchorCosts& costs, const QueryStop* stop) {
  if (rows.first < 0 || rows.last >= static_cast<int>(enhanced_rows.size()) || rows.first > rows.last ||
      rows.anchor < rows.first || rows.anchor > rows.last) {
    throw std::invalid_argument("test sequence rows are outside the difference matrix");
  }
  const int length = rows.last - rows.first + 1;
  // offsets[v][t - first]: the column of row t, relative to the anchor's, at velocity v.
  std::vector<std::vector<int>> offsets(velocities.size(), std::vector<int>(static_cast<std::size_t>(length)));
  for (std::size_t v = 0; v < velocities.size(); ++v) {
    for (int t = rows.first; t <= rows.last; ++t) {
      offsets[v][static_cast<std::size_t>(t - rows.first)] =
          static_cast<int>(std::lround(velocities[v] * (t - rows.anchor)));
    }
  }
  costs.cost.assign(static_cast<std::size_t>(std::max(0, columns)), std::numeric_limits<float>::infinity());
  costs.velocity.assign(costs.cost.size(), 0.0F);
  // Blocks of anchors are independent: each writes only its own costs, so threads share the work
  // and the result does not depend on how it is split.
  constexpr int kBlock = 256;
  const int blocks = (columns + kBlock - 1) / kBlock;
  cv::parallel_for_(cv::Range(0, blocks), [&](const cv::Range& range) {
    std::vector<float> sums(kBlock);
    std::vector<const float*> row_starts(static_cast<std::size_t>(length));
    for (int block = range.start; block < range.end && !stopRequested(stop); ++block) {
      const int block_begin = block * kBlock;
      const int block_end = std::min(columns, block_begin + kBlock);
      for (std::size_t v = 0; v < velocities.size(); ++v) {
        // Anchors of this block whose whole trajectory lies inside the reference.
        const int begin = std::max(block_begin, -offsets[v].front());
        const int end = std::min(block_end, columns - offsets[v].back());
        if (begin >= end) continue;
        // Row t's cells of anchors [begin, end): inside the row, as begin and end keep every
        // trajectory inside the matrix.
        for (int t = rows.first; t <= rows.last; ++t) {
          row_starts[static_cast<std::size_t>(t - rows.first)] = enhanced_rows[static_cast<std::size_t>(t)] +
                                                                  offsets[v][static_cast<std::size_t>(t - rows.first)] +
                                                                  begin;
        }
        sumRows(row_starts.data(), length, end - begin, sums.data());
        keepLowerMeans(sums.data(), end - begin, static_cast<float>(length), static_cast<float>(velocities[v]),
                       costs.cost.data() + begin, costs.velocity.data() + begin);
      }
    }
  });
  throwIfStopped(stop);
}

Match searchTrajectories(const cv::Mat& enhanced, const SequenceRows& rows, const SequenceParams& params,
                         const QueryStop* stop, const PlaceLinks* links) {
  Match match =
      scoreAnchorCosts(costsByAnchor(enhanced, rows, velocities(params), stop), params.match_exclusion, links);
  match.comparisons = static_cast<long long>(rows.last - rows.first + 1) * enhanced.cols;
  return match;
}

}  // namespace mrs_vpr
