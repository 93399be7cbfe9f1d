#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "mrs_vpr/acceptance.hpp"

namespace mrs_vpr {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

TEST(CostSpread, IsTheScaledMedianAbsoluteDeviationOfTheFiniteCosts) {
  // Median 3; absolute deviations {2, 1, 0, 1, 7}: median 1. The infinite cost is no trajectory.
  EXPECT_FLOAT_EQ(costSpread({1.0F, 2.0F, 3.0F, 4.0F, 10.0F, kInf}), 1.4826F);
}

TEST(CostSpread, AFewOutliersDoNotInflateIt) {
  std::vector<float> costs;
  for (int i = 0; i <= 100; ++i) costs.push_back(static_cast<float>(i));
  const float spread = costSpread(costs);
  EXPECT_FLOAT_EQ(spread, 1.4826F * 25.0F);
  for (int i = 0; i < 3; ++i) costs.push_back(-1000.0F);  // A true place far below every other end.
  EXPECT_NEAR(costSpread(costs), spread, 0.05F * spread);
}

TEST(CostSpread, EstimatesAGaussianStandardDeviationFromSamplesOfALargeTable) {
  std::mt19937_64 generator(5);
  std::normal_distribution<float> noise(10.0F, 2.0F);
  std::vector<float> costs(200000);
  for (float& cost : costs) cost = noise(generator);
  EXPECT_NEAR(costSpread(costs), 2.0F, 0.1F);
}

TEST(CostSpread, IsZeroWithoutEnoughFiniteCosts) {
  EXPECT_EQ(costSpread({}), 0.0F);
  EXPECT_EQ(costSpread({1.0F, 2.0F, kInf, kInf}), 0.0F);
}

TEST(Distinctiveness, IsTheGapInSpreads) {
  EXPECT_FLOAT_EQ(distinctiveness(1.0F, 4.0F, 0.5F, kMinRivalEnds), 6.0F);
  EXPECT_EQ(distinctiveness(1.0F, kInf, 0.5F, kMinRivalEnds), 0.0F);  // No rival: nothing to be sure about.
  EXPECT_EQ(distinctiveness(1.0F, 4.0F, 0.0F, kMinRivalEnds), 0.0F);  // No noise scale.
  EXPECT_EQ(distinctiveness(2.0F, 1.0F, 0.5F, kMinRivalEnds), 0.0F);  // A rival below the answer.
}

TEST(Distinctiveness, IsZeroAmongTooFewRivals) {
  // The least bad of a few wrong places can stand out by many spreads by chance.
  EXPECT_EQ(distinctiveness(1.0F, 4.0F, 0.5F, kMinRivalEnds - 1), 0.0F);
  EXPECT_EQ(distinctiveness(1.0F, 400.0F, 0.5F, 0), 0.0F);
}

TEST(ApplyAcceptance, AcceptsAFoundMatchAtTheThreshold) {
  Match match;
  match.reference_index = 7;
  match.confidence = 3.0F;
  applyAcceptance(match, 3.0);
  EXPECT_TRUE(match.accepted);
  applyAcceptance(match, 3.5);
  EXPECT_FALSE(match.accepted);
  match.reference_index = -1;
  applyAcceptance(match, 0.0);
  EXPECT_FALSE(match.accepted);  // Nothing found is never accepted.
}

}  // namespace
}  // namespace mrs_vpr
