#include <gtest/gtest.h>

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
      policy.skip();
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

TEST(KeyframePolicy, TimeRunningBackwardsRestarts) {
  KeyframePolicy policy(1.0, 1);
  EXPECT_EQ(keptFrames(policy, 3, 0.1, 100.0), (std::vector<int>{0}));
  EXPECT_TRUE(policy.wants(5.0));  // a bag replayed from its start
}

TEST(KeyframePolicy, ResetForgetsTheLastKeyframe) {
  KeyframePolicy policy(10.0, 1);
  policy.keep(1.0);
  EXPECT_FALSE(policy.wants(2.0));
  policy.reset();
  EXPECT_TRUE(policy.wants(2.0));
}

}  // namespace
}  // namespace node
}  // namespace mrs_vpr
