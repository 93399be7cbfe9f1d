#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <random>
#include <vector>

#include "mrs_vpr/node/keyframe_policy.hpp"

namespace mrs_vpr {
namespace node {
namespace {

/// Feeds frames stamped 0, dt, 2 dt, ... and returns the indices kept.
std::vector<int> keptFrames(KeyframePolicy& policy, int frames, double dt, double start = 0.0) {
  std::vector<int> kept;
  for (int i = 0; i < frames; ++i) {
    const double stamp = start + i * dt;
    if (policy.wants(stamp)) {
      policy.keep(stamp);
      kept.push_back(i);
    } else {
      policy.skip(stamp);
    }
  }
  return kept;
}

/// Stamps of a camera of period `dt` whose stamps jitter uniformly by up to +-`jitter` (seeded).
std::vector<double> jitteredStamps(int frames, double dt, double jitter, unsigned seed = 7) {
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> offset(-jitter, jitter);
  std::vector<double> stamps;
  for (int i = 0; i < frames; ++i) stamps.push_back(100.0 + i * dt + offset(generator));
  return stamps;
}

/// Stamps of the frames kept among `stamps`.
std::vector<double> keptStamps(KeyframePolicy& policy, const std::vector<double>& stamps) {
  std::vector<double> kept;
  for (const double stamp : stamps) {
    if (policy.wants(stamp)) {
      policy.keep(stamp);
      kept.push_back(stamp);
    } else {
      policy.skip(stamp);
    }
  }
  return kept;
}

TEST(KeyframePolicy, KeepsEveryFrameByDefault) {
  KeyframePolicy policy(0.0, 1);
  EXPECT_EQ(keptFrames(policy, 5, 0.1), (std::vector<int>{0, 1, 2, 3, 4}));
}

TEST(KeyframePolicy, Stride) {
  KeyframePolicy policy(0.0, 3);
  EXPECT_EQ(keptFrames(policy, 10, 0.1), (std::vector<int>{0, 3, 6, 9}));
}

TEST(KeyframePolicy, MinimumInterval) {
  KeyframePolicy policy(0.25, 1);  // a 10 Hz camera: every third frame (0.3 s apart)
  EXPECT_EQ(keptFrames(policy, 10, 0.1), (std::vector<int>{0, 3, 6, 9}));
}

TEST(KeyframePolicy, StrideAndIntervalBothApply) {
  KeyframePolicy policy(0.35, 2);
  EXPECT_EQ(keptFrames(policy, 10, 0.1), (std::vector<int>{0, 4, 8}));
}

TEST(KeyframePolicy, JitteredStampsOfACameraAsSlowAsTheIntervalKeepEveryFrame) {
  // 1 Hz camera, interval 1 s, stamps +-50 ms: one keyframe a second, not one every two seconds.
  KeyframePolicy policy(1.0, 1);
  const std::vector<double> stamps = jitteredStamps(100, 1.0, 0.05);
  EXPECT_EQ(keptStamps(policy, stamps), stamps);
}

TEST(KeyframePolicy, JitteredStampsOfAFastCameraGiveOneKeyframePerInterval) {
  // 30 Hz camera, interval 1 s, stamps +-3 ms, 60 s: keyframes 1 s apart on average, never much less.
  KeyframePolicy policy(1.0, 1);
  const std::vector<double> kept = keptStamps(policy, jitteredStamps(1800, 1.0 / 30.0, 0.003));
  ASSERT_GE(kept.size(), 59U);
  EXPECT_LE(kept.size(), 61U);
  std::vector<double> gaps;
  for (std::size_t i = 1; i < kept.size(); ++i) gaps.push_back(kept[i] - kept[i - 1]);
  EXPECT_GE(*std::min_element(gaps.begin(), gaps.end()), 0.95);
  EXPECT_LE(*std::max_element(gaps.begin(), gaps.end()), 1.05);
}

TEST(KeyframePolicy, JitterSlackIsAtMostATenthOfTheInterval) {
  KeyframePolicy policy(1.5, 1);  // a 1 Hz camera: 1 s is far from 1.5 s, so every second frame
  EXPECT_EQ(keptFrames(policy, 7, 1.0), (std::vector<int>{0, 2, 4, 6}));
  KeyframePolicy tolerant(1.05, 1);  // 1 s is within a tenth of 1.05 s: every frame
  EXPECT_EQ(keptFrames(tolerant, 4, 1.0), (std::vector<int>{0, 1, 2, 3}));
}

TEST(KeyframePolicy, TimeRunningBackwardsRestarts) {
  KeyframePolicy policy(1.0, 1);
  EXPECT_EQ(keptFrames(policy, 3, 0.1, 100.0), (std::vector<int>{0}));
  EXPECT_TRUE(policy.wants(5.0));  // a bag replayed from its start
  // Which the node warns about: the last keyframe's stamp, for the message.
  EXPECT_EQ(policy.steppedBackFrom(5.0), 100.0);
  EXPECT_EQ(policy.steppedBackFrom(100.5), std::nullopt);
  policy.reset();
  EXPECT_EQ(policy.steppedBackFrom(5.0), std::nullopt);  // A new map has no earlier keyframe.
}

TEST(KeyframePolicy, ResetForgetsTheLastKeyframe) {
  KeyframePolicy policy(10.0, 1);
  policy.keep(1.0);
  EXPECT_FALSE(policy.wants(2.0));
  policy.reset();
  EXPECT_TRUE(policy.wants(2.0));
}

TEST(KeyframePolicy, TheSlackIsHalfAFramePeriodSoTheFrameNearerTheIntervalIsKept) {
  // A camera of 0.15 s period, interval 1 s: half a period is 0.075 s, less than a tenth of the interval.
  KeyframePolicy policy(1.0, 1);
  policy.keep(10.0);
  policy.skip(10.76);
  EXPECT_FALSE(policy.wants(10.91));  // 0.09 s early: the next frame, 0.06 s late, is nearer
  policy.skip(10.91);
  EXPECT_TRUE(policy.wants(11.06));
  KeyframePolicy near(1.0, 1);
  near.keep(10.0);
  near.skip(10.79);
  EXPECT_TRUE(near.wants(10.94));  // 0.06 s early, within half a period: nearer than the next one
}

}  // namespace
}  // namespace node
}  // namespace mrs_vpr
