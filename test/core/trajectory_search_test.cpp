#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include <opencv2/core.hpp>

#include "mrs_vpr/acceptance.hpp"
#include "mrs_vpr/parameters.hpp"
#include "mrs_vpr/trajectory_search.hpp"

namespace mrs_vpr {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

/// Enhanced-looking matrix: values in [1, 2] with a trajectory of zeros through (anchor row, column)
/// at `velocity` (the same rounding as the search: column + round(v * (t - anchor))).
cv::Mat plantedMatrix(int rows, int columns, const SequenceRows& sequence, int column, double velocity) {
  cv::Mat matrix(rows, columns, CV_32F);
  cv::RNG rng(17);
  rng.fill(matrix, cv::RNG::UNIFORM, 1.0, 2.0);
  for (int t = sequence.first; t <= sequence.last; ++t) {
    matrix.at<float>(t, column + static_cast<int>(std::lround(velocity * (t - sequence.anchor)))) = 0.0F;
  }
  return matrix;
}

TEST(Velocities, DefaultFanHasFiveValuesEndingExactlyAtTheMaximum) {
  const SequenceParams params;  // 0.8 .. 1.2 step 0.1
  const std::vector<double> v = velocities(params);
  ASSERT_EQ(v.size(), 5U);
  const double expected[] = {0.8, 0.9, 1.0, 1.1, 1.2};
  for (std::size_t i = 0; i < v.size(); ++i) EXPECT_NEAR(v[i], expected[i], 1e-12) << i;
}

TEST(Velocities, SingleVelocityAndStepsThatDoNotReachTheMaximum) {
  SequenceParams params;
  params.velocity_min = 1.0;
  params.velocity_max = 1.0;
  EXPECT_EQ(velocities(params), std::vector<double>{1.0});
  params.velocity_min = 0.8;
  params.velocity_max = 1.2;
  params.velocity_step = 0.15;  // 0.8, 0.95, 1.1 (1.25 would overshoot).
  const std::vector<double> v = velocities(params);
  ASSERT_EQ(v.size(), 3U);
  EXPECT_NEAR(v.back(), 1.1, 1e-12);
}

TEST(SequenceRowsFor, CausalEndsAtTheFrameCentredSurroundsIt) {
  SequenceParams params;
  params.sequence_length = 10;
  params.alignment = WindowAlignment::kCausal;
  const SequenceRows causal = sequenceRowsFor(20, params);
  EXPECT_EQ(causal.first, 11);
  EXPECT_EQ(causal.last, 20);
  EXPECT_EQ(causal.anchor, 20);
  params.alignment = WindowAlignment::kCentred;
  const SequenceRows centred = sequenceRowsFor(20, params);
  EXPECT_EQ(centred.first, 15);
  EXPECT_EQ(centred.last, 24);
  EXPECT_EQ(centred.anchor, 20);
  params.sequence_length = 5;
  const SequenceRows odd = sequenceRowsFor(20, params);
  EXPECT_EQ(odd.first, 18);
  EXPECT_EQ(odd.last, 22);
  // Too close to the start: the rows tell the caller the sequence is incomplete.
  params.alignment = WindowAlignment::kCausal;
  EXPECT_LT(sequenceRowsFor(3, params).first, 0);
}

TEST(WholeSequenceRows, AnchorsAtTheNewestFrameOrAtCountOverTwo) {
  const SequenceRows causal = wholeSequenceRows(100, WindowAlignment::kCausal);
  EXPECT_EQ(causal.first, 0);
  EXPECT_EQ(causal.last, 99);
  EXPECT_EQ(causal.anchor, 99);
  const SequenceRows centred = wholeSequenceRows(100, WindowAlignment::kCentred);
  EXPECT_EQ(centred.last, 99);
  EXPECT_EQ(centred.anchor, 50);
  EXPECT_EQ(wholeSequenceRows(7, WindowAlignment::kCentred).anchor, 3);
  // The frame the per-frame protocol centres a sequence of the same length on.
  SequenceParams params;
  params.alignment = WindowAlignment::kCentred;
  params.sequence_length = 10;
  const SequenceRows per_frame = sequenceRowsFor(20, params);
  EXPECT_EQ(per_frame.anchor - per_frame.first, wholeSequenceRows(10, WindowAlignment::kCentred).anchor);
}

TEST(SearchTrajectories, FindsAPlantedCausalTrajectoryAndItsVelocity) {
  const SequenceRows rows{0, 9, 9};
  const cv::Mat matrix = plantedMatrix(10, 160, rows, 37, 0.9);
  const SequenceParams params;
  const Match match = searchTrajectories(matrix, rows, params);
  EXPECT_EQ(match.reference_index, 37);
  EXPECT_FLOAT_EQ(match.sequence_difference, 0.0F);
  EXPECT_FLOAT_EQ(match.score, 0.0F);
  EXPECT_GT(match.confidence, 3.0F);  // A planted path of zeros stands far out of the noise.
  EXPECT_EQ(match.comparisons, 10 * 160);
  const AnchorCosts costs = costsByAnchor(matrix, rows, velocities(params));
  EXPECT_FLOAT_EQ(costs.cost[37], 0.0F);
  EXPECT_FLOAT_EQ(costs.velocity[37], 0.9F);
}

TEST(SearchTrajectories, FindsAPlantedCentredTrajectory) {
  const SequenceRows rows{0, 9, 4};
  const cv::Mat matrix = plantedMatrix(10, 50, rows, 21, 1.2);
  SequenceParams params;
  params.alignment = WindowAlignment::kCentred;
  const Match match = searchTrajectories(matrix, rows, params);
  EXPECT_EQ(match.reference_index, 21);
  EXPECT_FLOAT_EQ(match.velocity, 1.2F);
  EXPECT_FLOAT_EQ(costsByAnchor(matrix, rows, velocities(params)).velocity[21], 1.2F);
}

TEST(SearchTrajectories, UsesOnlyTheRowsOfTheSequence) {
  // A planted trajectory in rows 5..14 of a 20-row matrix; other rows hold a decoy at column 10.
  cv::Mat matrix = plantedMatrix(20, 50, SequenceRows{5, 14, 14}, 40, 1.0);
  for (int t = 0; t < 20; ++t) {
    if (t < 5 || t > 14) matrix.at<float>(t, 10) = -100.0F;
  }
  EXPECT_EQ(searchTrajectories(matrix, SequenceRows{5, 14, 14}, SequenceParams{}).reference_index, 40);
}

TEST(CostsByAnchor, OnlyTrajectoriesInsideTheMatrixCount) {
  const SequenceRows rows{0, 9, 9};
  const cv::Mat matrix(10, 30, CV_32F, cv::Scalar(1.0F));
  const AnchorCosts costs = costsByAnchor(matrix, rows, velocities(SequenceParams{}));
  ASSERT_EQ(costs.cost.size(), 30U);
  // The slowest velocity reaches round(0.8 * 9) = 7 columns back from its anchor.
  for (int j = 0; j < 7; ++j) EXPECT_EQ(costs.cost[static_cast<std::size_t>(j)], kInf) << j;
  for (int j = 7; j < 30; ++j) EXPECT_FLOAT_EQ(costs.cost[static_cast<std::size_t>(j)], 1.0F) << j;
  // Column 7 fits only the slowest velocity.
  EXPECT_FLOAT_EQ(costs.velocity[7], 0.8F);
}

TEST(CostsByAnchor, CostIsTheMeanOfTheVisitedCells) {
  const SequenceRows rows{0, 2, 2};
  cv::Mat matrix = (cv::Mat_<float>(3, 4) << 1, 2, 3, 4,  //
                    5, 6, 7, 8,                           //
                    9, 10, 11, 12);
  // Velocity 1 only: the anchor column 3 visits (0, 1), (1, 2), (2, 3) -> (2 + 7 + 12) / 3.
  const AnchorCosts costs = costsByAnchor(matrix, rows, {1.0});
  EXPECT_EQ(costs.cost[0], kInf);
  EXPECT_EQ(costs.cost[1], kInf);
  EXPECT_FLOAT_EQ(costs.cost[2], (1.0F + 6.0F + 11.0F) / 3.0F);
  EXPECT_FLOAT_EQ(costs.cost[3], (2.0F + 7.0F + 12.0F) / 3.0F);
}

TEST(CostsByAnchor, RowsOutsideTheMatrixThrow) {
  const cv::Mat matrix(10, 30, CV_32F, cv::Scalar(1.0F));
  const std::vector<double> v{1.0};
  EXPECT_THROW(costsByAnchor(matrix, SequenceRows{0, 10, 10}, v), std::invalid_argument);
  EXPECT_THROW(costsByAnchor(matrix, SequenceRows{-1, 5, 5}, v), std::invalid_argument);
  EXPECT_THROW(costsByAnchor(matrix, SequenceRows{0, 5, 6}, v), std::invalid_argument);
}

TEST(ScoreFromCosts, ScoreIsBestOverRunnerUpOutsideHalfTheExclusion) {
  // Best 1 at index 2; 1.5 and 1.2 are within exclusion / 2 = 1 of it and do not count.
  const std::vector<float> costs{5.0F, 1.5F, 1.0F, 1.2F, 2.0F, 6.0F};
  const Match match = scoreFromCosts(costs, 2);
  EXPECT_EQ(match.reference_index, 2);
  EXPECT_FLOAT_EQ(match.sequence_difference, 1.0F);
  EXPECT_FLOAT_EQ(match.score, 0.5F);
  // Three rivals are too few to tell a place from chance (see kMinRivalEnds).
  EXPECT_FLOAT_EQ(match.confidence, 0.0F);
  // Without exclusion the neighbour is the runner-up.
  EXPECT_FLOAT_EQ(scoreFromCosts(costs, 0).score, 1.0F / 1.2F);
}

TEST(ScoreFromCosts, ExclusionBoundaryIsHalfTheWindow) {
  std::vector<float> costs(30, 10.0F);
  costs[10] = 1.0F;
  costs[15] = 2.0F;  // |15 - 10| = 5 = exclusion / 2: excluded.
  costs[16] = 4.0F;  // 6 > 5: the runner-up.
  const Match match = scoreFromCosts(costs, 10);
  EXPECT_EQ(match.reference_index, 10);
  EXPECT_FLOAT_EQ(match.score, 0.25F);
  // Most costs are equal: their spread is 0 and nothing can be told apart from the noise.
  EXPECT_FLOAT_EQ(match.confidence, 0.0F);
}

/// kMinRivalEnds + 3 ends of costs 10..14; end 1 costs 1, so that ends 0..2 are the answer's window
/// at exclusion 2 and every other end is a rival.
std::vector<float> tableWithDistinctEnd(int rivals) {
  std::vector<float> costs(static_cast<std::size_t>(rivals) + 3);
  for (std::size_t j = 0; j < costs.size(); ++j) costs[j] = 10.0F + static_cast<float>(j % 5);
  costs[1] = 1.0F;
  return costs;
}

TEST(ScoreFromCosts, ConfidenceIsTheGapInSpreadsOnceThereAreEnoughRivals) {
  const std::vector<float> costs = tableWithDistinctEnd(kMinRivalEnds);
  const Match match = scoreFromCosts(costs, 2);
  EXPECT_EQ(match.reference_index, 1);
  EXPECT_EQ(match.rivals, kMinRivalEnds);
  // Runner-up 10 (end 5).
  EXPECT_FLOAT_EQ(match.confidence, (10.0F - 1.0F) / costSpread(costs));
  EXPECT_GT(match.confidence, 3.0F);
  // One rival fewer and the same gap means nothing.
  EXPECT_FLOAT_EQ(scoreFromCosts(tableWithDistinctEnd(kMinRivalEnds - 1), 2).confidence, 0.0F);
}

TEST(ScoreFromCosts, EndsWithoutATrajectoryAreNoRivals) {
  std::vector<float> costs = tableWithDistinctEnd(kMinRivalEnds);
  costs.back() = kInf;
  const Match match = scoreFromCosts(costs, 2);
  EXPECT_EQ(match.rivals, kMinRivalEnds - 1);
  EXPECT_FLOAT_EQ(match.confidence, 0.0F);
}

TEST(ScoreFromCosts, NothingFitsOrNoRunnerUp) {
  EXPECT_EQ(scoreFromCosts({}, 10).reference_index, -1);
  EXPECT_EQ(scoreFromCosts({kInf, kInf}, 10).reference_index, -1);
  // A best but no runner-up: score 1, confidence 0.
  const Match alone = scoreFromCosts({kInf, 3.0F, 2.0F, kInf}, 10);
  EXPECT_EQ(alone.reference_index, 2);
  EXPECT_FLOAT_EQ(alone.score, 1.0F);
  EXPECT_FLOAT_EQ(alone.confidence, 0.0F);
}

TEST(ScoreFromCosts, TheFirstOfEqualLowestEndsWinsAndRivalsAreCountedOnBothSides) {
  // 1003 ends: the lowest cost twice, the second time among the last few ends, which a table read in
  // groups of several ends reads apart; a rival to either side of the winner.
  std::vector<float> costs(1003, 5.0F);
  costs[1001] = 1.0F;
  costs[700] = 1.0F;
  costs[3] = 2.0F;
  costs[1002] = kInf;
  const Match match = scoreFromCosts(costs, 10);
  EXPECT_EQ(match.reference_index, 700);
  EXPECT_EQ(match.rivals, 1003 - 11 - 1);  // All but the winner's 11 ends and the one with no trajectory.
  EXPECT_FLOAT_EQ(match.score, 1.0F);      // The other end at 1 is a rival.
  costs[1001] = 3.0F;
  EXPECT_FLOAT_EQ(scoreFromCosts(costs, 10).score, 0.5F);  // Now end 3's 2.
}

TEST(ScoreAround, ScoresAGivenWinner) {
  const std::vector<float> costs{4.0F, 3.0F, 2.0F, 8.0F, 8.0F, 8.0F, 1.0F};
  // Winner 1 (not the global minimum): best within +-1 is 2 (index 2), runner-up beyond is 1 (index 6).
  const Match match = scoreAround(costs, 1, 2);
  EXPECT_EQ(match.reference_index, 1);
  EXPECT_FLOAT_EQ(match.sequence_difference, 2.0F);
  EXPECT_FLOAT_EQ(match.score, 1.0F);  // 2 / 1, clamped.
  const Match good = scoreAround(costs, 6, 2);
  EXPECT_FLOAT_EQ(good.score, 0.5F);  // 1 / 2.
  EXPECT_FLOAT_EQ(good.confidence, 0.0F);  // Five rivals: too few.
  EXPECT_EQ(scoreAround(costs, 7, 2).reference_index, -1);
  EXPECT_EQ(scoreAround(costs, -1, 2).reference_index, -1);
}

// A place the map holds twice: the other visit costs as much as the answer, and is its rival until an
// accepted closure has linked the two visits; then the rival is the best other place.
TEST(ScoreAround, APlaceLinkedToTheAnswersIsNoRival) {
  std::vector<float> costs(400, 0.0F);
  for (std::size_t i = 0; i < costs.size(); ++i) costs[i] = 5.0F + static_cast<float>(i % 7) * 0.25F;
  costs[100] = 1.0F;
  costs[300] = 1.0F;  // the same place, on the second visit
  costs[200] = 4.0F;  // the best other place
  const Match unlinked = scoreAround(costs, 100, 10);
  EXPECT_FLOAT_EQ(unlinked.score, 1.0F);
  EXPECT_FLOAT_EQ(unlinked.confidence, 0.0F);
  PlaceLinks links;
  links.link(301, 101);
  const Match linked = scoreAround(costs, 100, 10, &links);
  EXPECT_FLOAT_EQ(linked.score, 1.0F / 4.0F);
  EXPECT_GT(linked.confidence, 3.0F);
  EXPECT_EQ(linked.rivals, unlinked.rivals - 11);  // the second visit's window
  EXPECT_FLOAT_EQ(scoreAround(costs, 300, 10, &links).confidence, linked.confidence);
  // In a table pooled over 4 frames the same frames are ends 75 and 25.
  std::vector<float> pooled(100);
  for (std::size_t end = 0; end < pooled.size(); ++end) pooled[end] = costs[4 * end];
  EXPECT_FLOAT_EQ(scoreAround(pooled, 25, 2, nullptr, 4).confidence, 0.0F);
  EXPECT_EQ(ownPlaceEnds(25, 2, 100, &links, 4).size(), 2U);
}

TEST(DistinctMinima, LowestFirstEachMoreThanTheSeparationFromTheOnesBefore) {
  std::vector<float> costs(40, 9.0F);
  costs[20] = 1.0F;
  costs[23] = 2.0F;  // |23 - 20| = 3 = separation: the same place as 20, skipped.
  costs[24] = 3.0F;  // 4 = separation + 1: a distinct place.
  costs[5] = 2.5F;
  costs[35] = 4.0F;
  EXPECT_EQ(distinctMinima(costs, 3, 4), (std::vector<int>{20, 5, 24, 35}));
  // The separation is measured from every end chosen so far, not only the first: 27 lies beyond 20's
  // reach but within 24's.
  costs[27] = 3.5F;
  EXPECT_EQ(distinctMinima(costs, 3, 4), (std::vector<int>{20, 5, 24, 35}));
  // Separation 0: only the very same end is excluded, so neighbours count.
  EXPECT_EQ(distinctMinima(costs, 0, 3), (std::vector<int>{20, 23, 5}));
}

TEST(DistinctMinima, CountLimitsTheResult) {
  const std::vector<float> costs{5.0F, 9.0F, 4.0F, 9.0F, 3.0F, 9.0F, 2.0F, 9.0F, 1.0F};
  EXPECT_EQ(distinctMinima(costs, 1, 2), (std::vector<int>{8, 6}));
  EXPECT_EQ(distinctMinima(costs, 1, 1), (std::vector<int>{8}));
  EXPECT_TRUE(distinctMinima(costs, 1, 0).empty());
  // Fewer distinct places than asked for: all of them, no padding.
  EXPECT_EQ(distinctMinima(costs, 1, 100), (std::vector<int>{8, 6, 4, 2, 0}));
}

TEST(DistinctMinima, InfiniteCostsAreNoPlaceAndEmptyTablesGiveNothing) {
  // Ends where no trajectory fits never count, however few finite ends remain.
  const std::vector<float> costs{kInf, 3.0F, kInf, kInf, kInf, kInf, 2.0F, kInf};
  EXPECT_EQ(distinctMinima(costs, 2, 5), (std::vector<int>{6, 1}));
  EXPECT_TRUE(distinctMinima({}, 2, 5).empty());
  EXPECT_TRUE(distinctMinima({kInf, kInf, kInf}, 2, 5).empty());
  // An infinite end does not block a finite neighbour either.
  EXPECT_EQ(distinctMinima({kInf, 1.0F}, 5, 2), (std::vector<int>{1}));
}

}  // namespace
}  // namespace mrs_vpr
