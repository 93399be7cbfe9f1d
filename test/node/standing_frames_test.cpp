#include "mrs_vpr/node/standing_frames.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace mrs_vpr {
namespace node {
namespace {

Stamp at(double seconds) { return Stamp::fromSeconds(seconds); }

using Stamps = std::vector<Stamp>;

TEST(StandingFrames, AStopIsKeptOncePerSpacingFromOneSpacingAfterItsKeyframe) {
  StandingFrames standing(1.0);
  standing.keyframe(at(10.0));
  for (double t = 10.1; t < 13.05; t += 0.1) standing.tooSimilar(at(t));  // a 3 s stop at 10 Hz
  const Stamps kept = standing.of(at(10.0));
  ASSERT_EQ(kept.size(), 3U);
  // Each at least a second after the one before; the first a second after the keyframe.
  EXPECT_GE(kept[0], at(11.0));
  EXPECT_LT(kept[0], at(11.15));
  EXPECT_GE(kept[1].nanoseconds() - kept[0].nanoseconds(), 1000000000LL);
  EXPECT_GE(kept[2].nanoseconds() - kept[1].nanoseconds(), 1000000000LL);
}

TEST(StandingFrames, AMovingRobotsFramesBetweenKeyframesAreNotAStop) {
  StandingFrames standing(1.0);
  for (int k = 0; k < 10; ++k) {
    standing.keyframe(at(10.0 + 0.3 * k));
    standing.tooSimilar(at(10.1 + 0.3 * k));
    standing.tooSimilar(at(10.2 + 0.3 * k));
  }
  for (int k = 0; k < 10; ++k) EXPECT_TRUE(standing.of(at(10.0 + 0.3 * k)).empty()) << k;
}

TEST(StandingFrames, FramesBelongToTheNewestKeyframeOnly) {
  StandingFrames standing(1.0);
  standing.keyframe(at(10.0));
  standing.tooSimilar(at(11.0));
  standing.keyframe(at(12.0));
  standing.tooSimilar(at(13.5));
  EXPECT_EQ(standing.of(at(10.0)), Stamps{at(11.0)});
  EXPECT_EQ(standing.of(at(12.0)), Stamps{at(13.5)});
  EXPECT_TRUE(standing.of(at(11.0)).empty());  // not a keyframe
}

TEST(StandingFrames, OnlyTheNewestKeyframesAndTheFirstFramesOfALongStopAreKept) {
  StandingFrames standing(1.0, 2, 3);
  standing.keyframe(at(1.0));
  standing.tooSimilar(at(2.0));
  standing.keyframe(at(3.0));
  for (int s = 4; s < 100; ++s) standing.tooSimilar(at(s));  // parked
  standing.keyframe(at(100.0));
  EXPECT_TRUE(standing.of(at(1.0)).empty());  // forgotten: more than 2 keyframes since
  EXPECT_EQ(standing.of(at(3.0)), (Stamps{at(4.0), at(5.0), at(6.0)}));
}

TEST(StandingFrames, NothingBeforeTheFirstKeyframeNorForUnstampedOrAfterClear) {
  StandingFrames standing(1.0);
  standing.tooSimilar(at(5.0));  // no keyframe yet: ignored
  standing.keyframe(Stamp());
  standing.tooSimilar(at(7.0));
  EXPECT_TRUE(standing.of(Stamp()).empty());
  standing.keyframe(at(8.0));
  standing.tooSimilar(at(9.0));
  standing.clear();
  EXPECT_TRUE(standing.of(at(8.0)).empty());
}

TEST(PendingRestatements, TheNewestKeyframesStopIsRestatedAsItComesNotOnlyWhenItsAnswerCame) {
  StandingFrames standing(1.0);
  PendingRestatements pending;
  standing.keyframe(at(10.0));
  pending.accepted(at(10.0));  // A causal question about the newest keyframe, before the stop.
  EXPECT_TRUE(pending.take(standing).empty());
  for (double t = 10.1; t < 12.55; t += 0.1) standing.tooSimilar(at(t));  // 2.5 s of the stop
  const Stamps first = pending.take(standing);
  ASSERT_EQ(first.size(), 2U);
  EXPECT_TRUE(pending.take(standing).empty());  // Each frame once.
  for (double t = 12.6; t < 13.55; t += 0.1) standing.tooSimilar(at(t));
  const Stamps second = pending.take(standing);
  ASSERT_EQ(second.size(), 1U);
  EXPECT_GT(second[0], first[1]);
  // The robot drives on: the next keyframe's frames are not this closure's.
  standing.keyframe(at(14.0));
  for (double t = 14.1; t < 16.05; t += 0.1) standing.tooSimilar(at(t));
  EXPECT_TRUE(pending.take(standing).empty());
}

TEST(PendingRestatements, AnAnswerAboutAnOlderKeyframeTakesItsWholeStopOnceAndClearForgetsIt) {
  StandingFrames standing(1.0);
  PendingRestatements pending;
  standing.keyframe(at(10.0));
  for (double t = 10.1; t < 13.05; t += 0.1) standing.tooSimilar(at(t));
  standing.keyframe(at(14.0));
  pending.accepted(at(10.0));  // A centred question, once the robot has driven on.
  EXPECT_EQ(pending.take(standing), standing.of(at(10.0)));
  EXPECT_TRUE(pending.take(standing).empty());
  pending.accepted(at(10.0));  // Accepted again (another question): restated again.
  EXPECT_EQ(pending.take(standing).size(), 3U);
  pending.clear();
  EXPECT_TRUE(pending.take(standing).empty());
}

// A closure that the robot's back end rejected is not restated for its stop any more; rejecting
// another keyframe's closure changes nothing.
TEST(PendingRestatements, ARejectedClosureIsNotRestatedForTheRestOfItsStop) {
  StandingFrames standing(1.0);
  PendingRestatements pending;
  standing.keyframe(at(10.0));
  pending.accepted(at(10.0));
  for (double t = 10.1; t < 12.55; t += 0.1) standing.tooSimilar(at(t));
  EXPECT_EQ(pending.take(standing).size(), 2U);
  EXPECT_FALSE(pending.reject(at(9.0)));
  for (double t = 12.6; t < 13.55; t += 0.1) standing.tooSimilar(at(t));
  EXPECT_TRUE(pending.reject(at(10.0)));
  EXPECT_TRUE(pending.take(standing).empty());
  EXPECT_FALSE(pending.reject(at(10.0)));
}

}  // namespace
}  // namespace node
}  // namespace mrs_vpr
