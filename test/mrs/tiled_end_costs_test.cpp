#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/core/utility.hpp>

#include "mrs_vpr/contrast_enhancement.hpp"
#include "mrs_vpr/mrs/tiled_end_costs.hpp"

namespace mrs_vpr {
namespace {

cv::Mat randomDifferences(int rows, int columns, int seed) {
  cv::Mat differences(rows, columns, CV_32F);
  cv::RNG rng(static_cast<std::uint64_t>(seed));
  rng.fill(differences, cv::RNG::UNIFORM, 0.5, 2.0);
  return differences;
}

DifferenceTile tileOf(const cv::Mat& differences, int* tiles = nullptr) {
  return [&differences, tiles](int begin, int end, cv::Mat& raw) {
    differences.colRange(begin, end).copyTo(raw);
    if (tiles != nullptr) ++*tiles;
  };
}

void expectSameCosts(const AnchorCosts& tiled, const AnchorCosts& whole, const std::string& where) {
  ASSERT_EQ(tiled.cost.size(), whole.cost.size()) << where;
  for (std::size_t j = 0; j < whole.cost.size(); ++j) {
    if (std::isinf(whole.cost[j])) {
      EXPECT_TRUE(std::isinf(tiled.cost[j])) << where << ", anchor " << j;  // Fits nowhere, in both.
      continue;
    }
    EXPECT_EQ(tiled.cost[j], whole.cost[j]) << where << ", anchor " << j;  // Tiles enhance as the whole.
    EXPECT_EQ(tiled.velocity[j], whole.velocity[j]) << where << ", anchor " << j;
  }
}

// Maps shorter than a tile, a few tiles and a partial last tile; causal and centred anchors; with
// and without contrast enhancement: the costs of the whole enhanced matrix, anchor by anchor.
TEST(TiledCostsByAnchor, EqualTheWholeMatrixCosts) {
  const std::vector<double> velocities{0.8, 0.9, 1.0, 1.1, 1.2};
  for (int columns : {40, 512, 1500}) {
    for (const SequenceRows rows : {SequenceRows{0, 19, 19}, SequenceRows{0, 19, 10}}) {
      for (int window : {0, 10}) {
        const cv::Mat differences = randomDifferences(20, columns, columns + window);
        const AnchorCosts whole = costsByAnchor(enhanceContrast(differences, window), rows, velocities);
        const AnchorCosts tiled = tiledCostsByAnchor(columns, rows, velocities, window, tileOf(differences));
        expectSameCosts(tiled, whole,
                        "columns " + std::to_string(columns) + ", anchor " + std::to_string(rows.anchor) + ", window " +
                            std::to_string(window));
      }
    }
  }
}

TEST(TiledCostsByAnchor, SameCostsWhateverTheThreadCount) {
  const std::vector<double> velocities{0.8, 1.0, 1.2};
  const cv::Mat differences = randomDifferences(30, 2000, 7);
  const SequenceRows rows{0, 29, 29};
  const int threads = cv::getNumThreads();
  cv::setNumThreads(1);
  int tiles = 0;
  const AnchorCosts one = tiledCostsByAnchor(2000, rows, velocities, 10, tileOf(differences, &tiles));
  cv::setNumThreads(4);
  const AnchorCosts four = tiledCostsByAnchor(2000, rows, velocities, 10, tileOf(differences));
  cv::setNumThreads(threads);
  EXPECT_GT(tiles, 1);  // The map spans several tiles.
  EXPECT_EQ(one.cost, four.cost);
  EXPECT_EQ(one.velocity, four.velocity);
}

}  // namespace
}  // namespace mrs_vpr
