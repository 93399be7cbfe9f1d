#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include <opencv2/core.hpp>

#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/difference_matrix.hpp"
#include "mrs_vpr/mrs/lazy_difference_matrix.hpp"
#include "mrs_vpr/mrs/patch_frequencies.hpp"
#include "mrs_vpr/mrs/particle_evaluation.hpp"
#include "mrs_vpr/mrs/sampling_level.hpp"
#include "mrs_vpr/trajectory_search.hpp"
#include "support/front_ends.hpp"

namespace mrs_vpr {
namespace {

using testing_support::thumbnailParams;

constexpr float kInf = std::numeric_limits<float>::infinity();

TEST(EndCostTable, DenseTablePicksTheLowestFeasibleCostNearTheCentre) {
  AnchorCosts costs;
  costs.cost = {0.0F, 5.0F, 4.0F, 3.0F, 6.0F, 2.5F, 7.0F, 0.5F};
  costs.velocity = {1.0F, 1.0F, 0.9F, 1.1F, 1.0F, 1.2F, 1.0F, 0.8F};
  SamplingLevel level;
  level.grid_size = 8;
  level.lowest_end = 1;  // Index 0 (cost 0) is not feasible.
  level.highest_end = 7;
  EndCostTable table(costs, level);
  const Evaluation near_start = table.bestInWindow(1, 2);
  EXPECT_EQ(near_start.index, 3);
  EXPECT_FLOAT_EQ(near_start.cost, 3.0F);
  EXPECT_FLOAT_EQ(near_start.velocity, 1.1F);
  EXPECT_EQ(table.bestInWindow(5, 2).index, 7);
  EXPECT_EQ(table.costs(), costs.cost);
}

TEST(EndCostTable, LazyCostsEqualTheDenseSearchOnTheEndsAsked) {
  // Random descriptors; the sequence is reference frames 30..41 with a different phase of noise.
  cv::RNG rng(23);
  DescriptorSequence reference(32);
  DescriptorSequence query(32);
  cv::Mat row(1, 32, CV_8U);
  for (int f = 0; f < 80; ++f) {
    rng.fill(row, cv::RNG::UNIFORM, 0, 256);
    reference.append(row);
  }
  for (int f = 0; f < 12; ++f) {
    cv::Mat noisy = reference.descriptorRow(30 + f).clone();
    noisy.at<std::uint8_t>(0, f) = static_cast<std::uint8_t>(noisy.at<std::uint8_t>(0, f) ^ 0x55);
    query.append(noisy);
  }
  const SequenceRows rows = wholeSequenceRows(12, WindowAlignment::kCausal);
  const SamplingLevel level = SamplingLevel::make(1, rows, reference.size(), 0.8);
  const std::vector<double> fan = velocities(SequenceParams{});
  const AnchorCosts dense =
      costsByAnchor(computeDifferenceMatrix(query.view(), reference.view()), level.sequenceRows(), fan);

  const PatchFrequencies unused{thumbnailParams()};  // Full resolution compares the frames themselves.
  LazyDifferenceMatrix matrix(query.view(), reference.view(), 1, unused, 0);
  EndCostTable lazy(matrix, level, fan);
  const Evaluation best = lazy.bestInWindow(40, 3);
  EXPECT_EQ(best.index, 41);
  EXPECT_FLOAT_EQ(best.velocity, 1.0F);
  for (int end = 37; end <= 43; ++end) {
    EXPECT_NEAR(lazy.costs()[static_cast<std::size_t>(end)], dense.cost[static_cast<std::size_t>(end)], 1e-5F) << end;
  }
  // Ends never asked for stay unknown (infinity); only the visited cells were compared.
  EXPECT_EQ(lazy.costs()[60], kInf);
  EXPECT_LT(matrix.comparisons(), 12 * 80 / 2);
  const long long after_first = matrix.comparisons();
  lazy.bestInWindow(41, 2);  // Every end already known: no new work.
  EXPECT_EQ(matrix.comparisons(), after_first);
}

TEST(FanSpread, TwoOverTheRowsAndAtLeastTwoGridStepsAfterTheCoarsestLevelOneAfterAFinerOne) {
  EXPECT_DOUBLE_EQ(fanSpread(0.02, 38, true), 2.0 / 38);  // 2 / L beyond two steps.
  EXPECT_DOUBLE_EQ(fanSpread(0.02, 75, true), 0.04);      // Two steps.
  EXPECT_DOUBLE_EQ(fanSpread(0.02, 75, false), 2.0 / 75);
  EXPECT_DOUBLE_EQ(fanSpread(0.02, 150, false), 0.02);  // One step.
  EXPECT_DOUBLE_EQ(fanSpread(0.1, 50, false), 0.1);
}

TEST(VelocitiesNear, KeepsTheFanWithinTheSpreadOrTheNearest) {
  const std::vector<double> all{0.8, 0.9, 1.0, 1.1, 1.2};
  const std::vector<double> near = velocitiesNear(all, 1.0, 0.1);
  ASSERT_EQ(near.size(), 3U);
  EXPECT_NEAR(near.front(), 0.9, 1e-12);
  EXPECT_NEAR(near.back(), 1.1, 1e-12);
  EXPECT_EQ(velocitiesNear(all, 2.0, 0.1), std::vector<double>{1.2});
}

}  // namespace
}  // namespace mrs_vpr
