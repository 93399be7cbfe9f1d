#include <cmath>
#include <limits>
#include <random>
#include <string>
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

/// A found match among the rivals of a large map (the threshold applies as it is).
Match foundMatch() {
  Match match;
  match.reference_index = 7;
  match.rivals = 5000;
  match.rival_places = 500;
  return match;
}

TEST(ApplyAcceptance, AcceptsAFoundMatchAtTheThreshold) {
  SequenceParams params;  // Velocities 0.8 .. 1.2.
  Match match = foundMatch();
  match.confidence = 3.0F;
  match.velocity = 1.0F;
  params.accept_threshold = 3.0;
  applyAcceptance(match, params);
  EXPECT_TRUE(match.accepted);
  params.accept_threshold = 3.5;
  applyAcceptance(match, params);
  EXPECT_FALSE(match.accepted);
  match.reference_index = -1;
  params.accept_threshold = 0.0;
  applyAcceptance(match, params);
  EXPECT_FALSE(match.accepted);  // Nothing found is never accepted.
}

TEST(ApplyAcceptance, RefusesATrajectoryAtTheSlowestOrFastestVelocity) {
  SequenceParams params;  // 0.8, 0.9, 1.0, 1.1, 1.2
  Match match = foundMatch();
  match.confidence = 10.0F;
  for (float velocity : {0.8F, 1.2F}) {
    match.velocity = velocity;
    match.confidence = 10.0F;
    EXPECT_TRUE(atVelocityBound(match, params)) << velocity;
    applyAcceptance(match, params);
    EXPECT_FALSE(match.accepted) << velocity;
    EXPECT_TRUE(match.at_velocity_bound) << velocity;
    EXPECT_EQ(match.confidence, 0.0F) << velocity;  // Nothing to be sure about, as among too few rivals.
    params.accept_threshold = 0.0;  // Not even when every confidence is enough.
    applyAcceptance(match, params);
    EXPECT_FALSE(match.accepted) << velocity;
    params.accept_threshold = 3.0;
  }
  for (float velocity : {0.9F, 1.0F, 1.1F}) {
    match.velocity = velocity;
    match.confidence = 10.0F;
    EXPECT_FALSE(atVelocityBound(match, params)) << velocity;
    applyAcceptance(match, params);
    EXPECT_TRUE(match.accepted) << velocity;
    EXPECT_FALSE(match.at_velocity_bound) << velocity;
    EXPECT_EQ(match.confidence, 10.0F) << velocity;
  }
  // A finer grid: its own bounds, not 0.8 + one coarse step.
  params.velocity_step = 0.02;
  match.velocity = 0.82F;
  EXPECT_FALSE(atVelocityBound(match, params));
  match.velocity = 0.8F;
  EXPECT_TRUE(atVelocityBound(match, params));
}

TEST(ApplyAcceptance, OneOrTwoVelocitiesAreTheUsersFixedSpeedNotABound) {
  SequenceParams params;
  params.velocity_min = 1.0;
  params.velocity_max = 1.0;
  Match match = foundMatch();
  match.confidence = 10.0F;
  match.velocity = 1.0F;
  applyAcceptance(match, params);
  EXPECT_TRUE(match.accepted);
  params.velocity_max = 1.1;  // 1.0 and 1.1.
  match.velocity = 1.1F;
  applyAcceptance(match, params);
  EXPECT_TRUE(match.accepted);
}

TEST(RequiredConfidence, RisesOnMapsOfFewerThanAHundredPlaces) {
  SequenceParams params;  // accept_threshold 3, match_exclusion 10
  EXPECT_EQ(placesAmong(500, 1, params.match_exclusion), 100);  // ends within 5 frames show one place
  EXPECT_EQ(placesAmong(125, 4, params.match_exclusion), 100);  // a coarse table's ends stand for 4 frames each
  EXPECT_DOUBLE_EQ(requiredConfidence(100, params), 3.0);
  EXPECT_DOUBLE_EQ(requiredConfidence(100000, params), 3.0);
  // The bound exp(-d sqrt(2 ln n)) kept at its value for 100 places.
  EXPECT_NEAR(requiredConfidence(10, params), 3.0 * std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(requiredConfidence(50, params), 3.0 * std::sqrt(std::log(100.0) / std::log(50.0)), 1e-9);
  EXPECT_GT(requiredConfidence(20, params), requiredConfidence(50, params));
  EXPECT_TRUE(std::isinf(requiredConfidence(1, params)));
  params.accept_threshold = 0.0;  // the user accepts everything found
  EXPECT_EQ(requiredConfidence(1, params), 0.0);
}

TEST(ApplyAcceptance, AFewDozenPlacesNeedMoreConfidence) {
  SequenceParams params;
  Match match = foundMatch();
  match.velocity = 1.0F;
  match.confidence = 3.5F;
  match.rival_places = 100;
  applyAcceptance(match, params);
  EXPECT_TRUE(match.accepted);
  match.rival_places = 12;  // needs 3 x 1.36 = 4.07
  applyAcceptance(match, params);
  EXPECT_FALSE(match.accepted);
  const std::string verdict = acceptanceVerdict(match, params);
  EXPECT_NE(verdict.find("raised for a map of about 12 places"), std::string::npos) << verdict;
  match.confidence = 4.2F;
  applyAcceptance(match, params);
  EXPECT_TRUE(match.accepted);
}

TEST(AcceptanceVerdict, SaysWhyAnAnswerIsNotAccepted) {
  SequenceParams params;
  Match match;
  EXPECT_EQ(acceptanceVerdict(match, params), "no match found");
  match.reference_index = 7;
  match.rivals = kMinRivalEnds - 1;
  EXPECT_NE(acceptanceVerdict(match, params).find("ends outside the answer's window"), std::string::npos);
  match.rivals = 1;
  EXPECT_NE(acceptanceVerdict(match, params).find("the map holds 1 end outside the answer's window"),
            std::string::npos);
  match.rivals = kMinRivalEnds;
  match.rival_places = kPlacesForPlainThreshold;
  match.confidence = 2.0F;
  match.velocity = 1.0F;
  EXPECT_EQ(acceptanceVerdict(match, params), "not accepted: confidence below sequence/accept_threshold");
  match.confidence = 5.0F;
  match.velocity = 0.8F;
  applyAcceptance(match, params);
  const std::string at_bound = acceptanceVerdict(match, params);
  EXPECT_NE(at_bound.find("runs at 0.8 map frames a frame, the slowest or fastest of"), std::string::npos) << at_bound;
  EXPECT_NE(at_bound.find("(0.8..1.2)"), std::string::npos) << at_bound;
  // On new ground the least bad place often lies at a bound too: the message names that cause as well.
  EXPECT_NE(at_bound.find("or the place may not be in the map"), std::string::npos) << at_bound;
  match.velocity = 1.0F;
  match.confidence = 5.0F;
  applyAcceptance(match, params);
  EXPECT_EQ(acceptanceVerdict(match, params), "accepted");
  match.accepted = false;
  match.repeated_view = true;
  const std::string repeated = acceptanceVerdict(match, params);
  EXPECT_NE(repeated.find("keyframes show one view again"), std::string::npos) << repeated;
}

}  // namespace
}  // namespace mrs_vpr
