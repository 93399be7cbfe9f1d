#include "mrs_vpr/mrs/tiled_end_costs.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <opencv2/core/utility.hpp>

#include "mrs_vpr/contrast_enhancement.hpp"

namespace mrs_vpr {
namespace {

// Anchors per tile: small enough for the cache, large enough that the overlap stays small.
constexpr int kTileAnchors = 512;

/// How far a trajectory reaches before (back) and after (ahead) its anchor's column.
struct Reach {
  int back = 0;
  int ahead = 0;
};

Reach trajectoryReach(const SequenceRows& rows, const std::vector<double>& velocities) {
  Reach reach;
  for (double velocity : velocities) {
    reach.back = std::max(reach.back, static_cast<int>(-std::lround(velocity * (rows.first - rows.anchor))));
    reach.ahead = std::max(reach.ahead, static_cast<int>(std::lround(velocity * (rows.last - rows.anchor))));
  }
  return reach;
}

}  // namespace

AnchorCosts tiledCostsByAnchor(int columns, const SequenceRows& rows, const std::vector<double>& velocities,
                               int contrast_window, const DifferenceTile& tile, const QueryStop* stop) {
  AnchorCosts costs;
  tiledCostsByAnchor(columns, rows, velocities, contrast_window, tile, costs, stop);
  return costs;
}

void tiledCostsByAnchor(int columns, const SequenceRows& rows, const std::vector<double>& velocities,
                        int contrast_window, const DifferenceTile& tile, AnchorCosts& costs,
                        const QueryStop* stop) {
  costs.cost.assign(static_cast<std::size_t>(std::max(0, columns)), std::numeric_limits<float>::infinity());
  costs.velocity.assign(costs.cost.size(), 0.0F);
  const Reach reach = trajectoryReach(rows, velocities);
  const int half = contrast_window / 2;
  const int tiles = (columns + kTileAnchors - 1) / kTileAnchors;
  // Each row's raw difference at column 0: every tile's piece of a row is enhanced relative to it,
  // so that the pieces are the whole row's cells.
  cv::Mat first_differences(rows.last + 1, 1, CV_32F);
  if (columns > 0) tile(0, 1, first_differences);
  cv::parallel_for_(cv::Range(0, tiles), [&](const cv::Range& range) {
    // Kept by each thread between tiles and queries (a Mat would reallocate whenever a tile's width
    // changes, as it does at the map's edges).
    thread_local std::vector<float> raw_storage;
    thread_local std::vector<float> enhanced_storage;
    for (int t = range.start; t < range.end && !stopRequested(stop); ++t) {
      const int anchor_begin = t * kTileAnchors;
      const int anchor_end = std::min(columns, anchor_begin + kTileAnchors);
      // Columns the tile's trajectories visit, and the raw columns their contrast windows see.
      const int visited_begin = std::max(0, anchor_begin - reach.back);
      const int visited_end = std::min(columns, anchor_end + reach.ahead);
      const int raw_begin = std::max(0, visited_begin - half);
      const int raw_end = std::min(columns, visited_end + half);
      raw_storage.resize(static_cast<std::size_t>(rows.last + 1) * static_cast<std::size_t>(raw_end - raw_begin));
      cv::Mat raw(rows.last + 1, raw_end - raw_begin, CV_32F, raw_storage.data());
      tile(raw_begin, raw_end, raw);
      enhanced_storage.resize(static_cast<std::size_t>(raw.rows) *
                              static_cast<std::size_t>(visited_end - visited_begin));
      cv::Mat enhanced(raw.rows, visited_end - visited_begin, CV_32F, enhanced_storage.data());
      for (int row = 0; row < raw.rows; ++row) {
        enhanceRowSpan(raw.ptr<float>(row), columns, visited_begin, visited_end, contrast_window,
                       first_differences.at<float>(row), enhanced.ptr<float>(row));
      }
      // Anchors whose trajectories fit in these columns are those that fit in the whole matrix:
      // the columns reach as far as any trajectory of the tile's anchors, or to the matrix's edge.
      const AnchorCosts part = costsByAnchor(enhanced, rows, velocities);
      for (int anchor = anchor_begin; anchor < anchor_end; ++anchor) {
        const auto from = static_cast<std::size_t>(anchor - visited_begin);
        costs.cost[static_cast<std::size_t>(anchor)] = part.cost[from];
        costs.velocity[static_cast<std::size_t>(anchor)] = part.velocity[from];
      }
    }
  });
  throwIfStopped(stop);
}

}  // namespace mrs_vpr
