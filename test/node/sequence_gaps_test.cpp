#include <gtest/gtest.h>

#include "mrs_vpr/node/sequence_gaps.hpp"

namespace mrs_vpr {
namespace node {
namespace {

TEST(SequenceGaps, CountsTheMessagesMissingFromAStream) {
  SequenceGaps gaps;
  EXPECT_EQ(gaps.record(40), 0U);  // the first message seen: nothing known before it
  EXPECT_EQ(gaps.record(41), 0U);  // the first steps teach the stream's stride, 1
  EXPECT_EQ(gaps.record(42), 0U);
  EXPECT_EQ(gaps.record(45), 2U);  // 43 and 44 never arrived
  EXPECT_EQ(gaps.record(46), 0U);
  // A burst of losses right after the first steps, as a node that starts slowly meets: each gap
  // counts, none is taken for the stream's cadence.
  EXPECT_EQ(gaps.record(51), 4U);
  EXPECT_EQ(gaps.record(56), 4U);
  EXPECT_EQ(gaps.record(61), 4U);
  EXPECT_EQ(gaps.record(62), 0U);
}

TEST(SequenceGaps, ANewOrReplayedStreamIsNoGap) {
  SequenceGaps gaps;
  gaps.record(500);
  EXPECT_EQ(gaps.record(0), 0U);  // a new publisher, or the bag played again
  EXPECT_EQ(gaps.record(1), 0U);
  EXPECT_EQ(gaps.record(1), 0U);  // a seq that never changes (messages within a nodelet manager)
  EXPECT_EQ(gaps.record(1), 0U);
}

TEST(SequenceGaps, AJumpBackThatWrapsIsARestartedSender) {
  SequenceGaps gaps;
  gaps.record(4000);
  EXPECT_EQ(gaps.record(4001), 0U);
  EXPECT_EQ(gaps.record(4294967295U), 0U);  // 4002 back, below 0: not 4294963293 lost frames
  EXPECT_EQ(gaps.record(0), 0U);            // the counter wrapping around
  EXPECT_EQ(gaps.record(1), 0U);
  EXPECT_EQ(gaps.record(4), 2U);            // and counting gaps again after it
  EXPECT_EQ(gaps.record(2147483652U), 0U);  // half the counter ahead is as far back
  EXPECT_EQ(gaps.record(2147483653U), 0U);
}

TEST(SequenceGaps, AGapAcrossTheWrapIsCounted) {
  SequenceGaps gaps;
  gaps.record(4294967288U);
  gaps.record(4294967289U);
  gaps.record(4294967290U);
  EXPECT_EQ(gaps.record(4U), 9U);  // 4294967291 .. 4294967295 and 0 .. 3
}

TEST(SequenceGaps, TwoPublishersAtOnceLoseNothingBetweenThem) {
  // A bag numbered from 300 played while the camera, numbered from 5, runs: they alternate.
  SequenceGaps gaps;
  EXPECT_EQ(gaps.record(5), 0U);
  // The first jump ahead is the first step of the camera's numbering as far as anything yet tells,
  // and a numbering's first steps count nothing (before a stream's stride was learnt, it counted 294).
  EXPECT_EQ(gaps.record(300), 0U);
  EXPECT_EQ(gaps.record(6), 0U);
  for (std::uint32_t i = 1; i < 100; ++i) {
    EXPECT_EQ(gaps.record(300 + i), 0U) << i;  // before, each of these counted 294 lost frames
    EXPECT_EQ(gaps.record(6 + i), 0U) << i;
  }
  EXPECT_EQ(gaps.record(403), 3U);  // a real gap in one of them is still counted: 400 .. 402
  EXPECT_EQ(gaps.record(106), 0U);
}

TEST(SequenceGaps, AJumpTheStampsDoNotBearOutIsAnotherRecording) {
  SequenceGaps gaps;
  const double summer = 1600000000.0;  // one recording at 10 Hz, numbered from 1000 ...
  for (std::uint32_t i = 0; i <= 10; ++i) EXPECT_EQ(gaps.record(1000 + i, summer + 0.1 * i), 0U) << i;
  EXPECT_EQ(gaps.record(1013, summer + 1.3), 2U);  // lost frames: three periods for three steps
  // ... then another, numbered from 5000 and recorded a day later: not 3986 lost frames.
  const double winter = summer + 86400.0;
  EXPECT_EQ(gaps.record(5000, winter), 0U);
  EXPECT_EQ(gaps.record(5001, winter + 0.1), 0U);  // its first steps teach its stride
  EXPECT_EQ(gaps.record(5002, winter + 0.2), 0U);
  EXPECT_EQ(gaps.record(5004, winter + 0.4), 1U);  // its own losses count again
  // A jump back in time, or a gap far shorter than the frames it skips, is no loss either.
  EXPECT_EQ(gaps.record(5005, winter + 0.5), 0U);
  EXPECT_EQ(gaps.record(5100, winter + 0.6), 0U);
  // Without stamps only the seq is known, and a jump counts (once the steps after the last jump,
  // which started the numbering afresh, taught its stride).
  EXPECT_EQ(gaps.record(5101), 0U);
  EXPECT_EQ(gaps.record(5102), 0U);
  EXPECT_EQ(gaps.record(6002), 899U);
}

TEST(SequenceGaps, ALossLongerThanTheInterleavedStepIsStillCountedOnTheNewestStream) {
  // A camera at 10 Hz whose subscriber stalls for 150 s: 1500 frames lost, the stamps bear it out.
  SequenceGaps gaps;
  const double start = 1600000000.0;
  for (std::uint32_t i = 0; i <= 10; ++i) EXPECT_EQ(gaps.record(100 + i, start + 0.1 * i), 0U) << i;
  EXPECT_EQ(gaps.record(1611, start + 1.0 + 150.1), 1500U);
  EXPECT_EQ(gaps.record(1612, start + 1.0 + 150.2), 0U);
  // Without stamps the seq alone tells it.
  SequenceGaps unstamped;
  EXPECT_EQ(unstamped.record(5), 0U);
  EXPECT_EQ(unstamped.record(6), 0U);
  EXPECT_EQ(unstamped.record(7), 0U);
  EXPECT_EQ(unstamped.record(2008), 2000U);
}

TEST(SequenceGaps, AStreamThinnedOnPurposeLosesNothingAndItsOwnGapsStillCount) {
  // A 30 Hz camera through `topic_tools throttle messages /camera 10`, as recorded here: the throttle
  // passes the camera's seq on, 71, 74, 78, 81, 84, 88, ...
  SequenceGaps throttled;
  const double start = 1600000000.0;
  std::uint32_t seq = 71;
  EXPECT_EQ(throttled.record(seq, start + seq / 30.0), 0U);
  for (int i = 1; i <= 60; ++i) {
    seq += i % 3 == 0 ? 4 : 3;  // a throttle's jitter: 3 or 4 camera frames a message
    EXPECT_EQ(throttled.record(seq, start + seq / 30.0), 0U) << i;
  }
  // A message of the throttled stream lost on the way: 3 or 4 more seqs on top of the step.
  seq += 7;
  EXPECT_EQ(throttled.record(seq, start + seq / 30.0), 1U);
  seq += 3;
  EXPECT_EQ(throttled.record(seq, start + seq / 30.0), 0U);
  // A jump the stamps do not bear out is still another recording, thinned or not.
  EXPECT_EQ(throttled.record(seq + 3000, start + 86400.0), 0U);

  // `topic_tools drop /camera 1 3` keeps two messages of three: steps of 1 and 2 by turns.
  SequenceGaps dropped;
  seq = 0;
  for (int i = 0; i < 40; ++i) {
    seq += i % 2 == 0 ? 1 : 2;
    EXPECT_EQ(dropped.record(seq), 0U) << i;
  }
  seq += 6;  // two messages of the kept ones lost: 6 seqs ahead at a stride of 2
  EXPECT_EQ(dropped.record(seq), 2U);
}

TEST(SequenceGaps, AStreamThinnedFromSomePointOnIsLearntWithinAQuarterOfTheRecentSteps) {
  SequenceGaps gaps;
  std::uint32_t seq = 0;
  for (int i = 0; i < 30; ++i) EXPECT_EQ(gaps.record(++seq), 0U);
  // Every third message from now on: counted as loss until steps of 3 are a quarter of the recent ones.
  std::uint64_t counted = 0;
  int steps_counted = 0;
  for (int i = 0; i < 30; ++i) {
    seq += 3;
    const std::uint64_t missing = gaps.record(seq);
    counted += missing;
    if (missing > 0) ++steps_counted;
  }
  EXPECT_EQ(steps_counted, SequenceGaps::kStrideSteps / 4);
  EXPECT_EQ(counted, 2U * (SequenceGaps::kStrideSteps / 4));
  // And a stream of every message again counts nothing, and its gaps again once it is learnt.
  for (int i = 0; i < 30; ++i) EXPECT_EQ(gaps.record(++seq), 0U) << i;
  EXPECT_EQ(gaps.record(seq + 3), 2U);
}

TEST(SequenceGaps, BehindABusyNodeEveryStepBeyondTheUpstreamCadenceIsLoss) {
  // A node slower than its camera from the first frame: its full queue passes every other message.
  // Those messages waited in the queue, so their steady step of 2 is loss, not the stream's cadence.
  SequenceGaps saturated;
  std::uint32_t seq = 0;
  saturated.record(seq);
  std::uint64_t lost = 0;
  for (int i = 0; i < 40; ++i) lost += saturated.record(seq += 2, 0.0, true);
  EXPECT_EQ(lost, 40U);

  // A throttled stream (every third seq) that the node kept up with, then fell behind.
  SequenceGaps throttled;
  seq = 0;
  throttled.record(seq);
  for (int i = 0; i < 20; ++i) EXPECT_EQ(throttled.record(seq += 3), 0U) << i;
  for (int i = 0; i < 20; ++i) EXPECT_EQ(throttled.record(seq += 6, 0.0, true), 1U) << i;
  EXPECT_EQ(throttled.record(seq += 3, 0.0, true), 0U);
  // And a step of the node's queue teaches nothing: idle again, a step of 6 is still loss.
  EXPECT_EQ(throttled.record(seq += 6), 1U);
}

}  // namespace
}  // namespace node
}  // namespace mrs_vpr
