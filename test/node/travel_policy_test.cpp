#include <gtest/gtest.h>

#include <vector>

#include "mrs_vpr/node/travel_policy.hpp"

namespace mrs_vpr {
namespace node {
namespace {

/// Feeds frames taken at x = positions[i] (y = z = 0) and returns the indices kept.
std::vector<int> keptFrames(TravelPolicy& policy, const std::vector<double>& positions) {
  std::vector<int> kept;
  for (int i = 0; i < static_cast<int>(positions.size()); ++i) {
    const Eigen::Vector3d position(positions[static_cast<std::size_t>(i)], 0.0, 0.0);
    if (policy.wants(position)) {
      policy.keep(position);
      kept.push_back(i);
    }
  }
  return kept;
}

TEST(TravelPolicy, KeepsEveryFrameWhenOff) {
  TravelPolicy policy(0.0);
  EXPECT_FALSE(policy.enabled());
  EXPECT_EQ(keptFrames(policy, {0.0, 0.0, 0.0, 0.1}), (std::vector<int>{0, 1, 2, 3}));
}

TEST(TravelPolicy, KeepsAFrameEachTimeTheRobotHasTravelledTheDistance) {
  TravelPolicy policy(1.0);
  EXPECT_TRUE(policy.enabled());
  EXPECT_EQ(keptFrames(policy, {0.0, 0.4, 0.8, 1.2, 1.6, 2.0, 2.4}), (std::vector<int>{0, 3, 6}));
}

TEST(TravelPolicy, AStoppedRobotAddsNoFrames) {
  TravelPolicy policy(0.5);
  // Driving, standing still for a while (with odometry noise), driving on.
  EXPECT_EQ(keptFrames(policy, {0.0, 0.5, 1.0, 1.01, 0.99, 1.0, 1.02, 1.0, 1.5, 2.0}),
            (std::vector<int>{0, 1, 2, 8, 9}));
}

TEST(TravelPolicy, ASpeedChangeKeepsTheSpacing) {
  TravelPolicy slow(1.0);
  TravelPolicy fast(1.0);
  std::vector<double> slow_positions;
  std::vector<double> fast_positions;
  for (int i = 0; i <= 40; ++i) slow_positions.push_back(0.25 * i);
  for (int i = 0; i <= 10; ++i) fast_positions.push_back(1.0 * i);
  // Both keep a frame every metre: 11 frames over 10 m, at a quarter or the whole metre per frame.
  EXPECT_EQ(keptFrames(slow, slow_positions).size(), 11U);
  EXPECT_EQ(keptFrames(fast, fast_positions).size(), 11U);
}

TEST(TravelPolicy, MeasuresTheStraightLineInThreeDimensions) {
  TravelPolicy policy(1.0);
  policy.keep(Eigen::Vector3d(0.0, 0.0, 0.0));
  EXPECT_FALSE(policy.wants(Eigen::Vector3d(0.6, 0.6, 0.3)));  // 0.9 m
  EXPECT_TRUE(policy.wants(Eigen::Vector3d(0.6, 0.6, 0.6)));   // 1.04 m
  EXPECT_TRUE(policy.wants(Eigen::Vector3d(0.0, -1.0, 0.0)));  // backwards counts too
}

TEST(TravelPolicy, ResetKeepsTheNextFrame) {
  TravelPolicy policy(1.0);
  policy.keep(Eigen::Vector3d(5.0, 0.0, 0.0));
  EXPECT_FALSE(policy.wants(Eigen::Vector3d(5.1, 0.0, 0.0)));
  policy.reset();
  EXPECT_TRUE(policy.wants(Eigen::Vector3d(5.1, 0.0, 0.0)));
}

}  // namespace
}  // namespace node
}  // namespace mrs_vpr
