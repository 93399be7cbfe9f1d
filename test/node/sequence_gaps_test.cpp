#include <gtest/gtest.h>

#include "mrs_vpr/node/sequence_gaps.hpp"

namespace mrs_vpr {
namespace node {
namespace {

TEST(SequenceGaps, CountsTheMessagesMissingFromAStream) {
  SequenceGaps gaps;
  EXPECT_EQ(gaps.record(41), 0U);  // the first message seen: nothing known before it
  EXPECT_EQ(gaps.record(42), 0U);
  EXPECT_EQ(gaps.record(45), 2U);  // 43 and 44 never arrived
  EXPECT_EQ(gaps.record(46), 0U);
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
  EXPECT_EQ(gaps.record(3), 2U);            // and counting gaps again after it
  EXPECT_EQ(gaps.record(2147483651U), 0U);  // half the counter ahead is as far back
  EXPECT_EQ(gaps.record(2147483652U), 0U);
}

TEST(SequenceGaps, AGapAcrossTheWrapIsCounted) {
  SequenceGaps gaps;
  gaps.record(4294967290U);
  EXPECT_EQ(gaps.record(4U), 9U);  // 4294967291 .. 4294967295 and 0 .. 3
}

TEST(SequenceGaps, TwoPublishersAtOnceLoseNothingBetweenThem) {
  // A bag numbered from 300 played while the camera, numbered from 5, runs: they alternate.
  SequenceGaps gaps;
  EXPECT_EQ(gaps.record(5), 0U);
  // The first jump ahead looks like a gap: nothing yet tells a second publisher. Only that one counts.
  EXPECT_EQ(gaps.record(300), 294U);
  EXPECT_EQ(gaps.record(6), 0U);
  for (std::uint32_t i = 1; i < 100; ++i) {
    EXPECT_EQ(gaps.record(300 + i), 0U) << i;  // before, each of these counted 294 lost frames
    EXPECT_EQ(gaps.record(6 + i), 0U) << i;
  }
  EXPECT_EQ(gaps.record(403), 3U);  // a real gap in one of them is still counted: 400 .. 402
  EXPECT_EQ(gaps.record(106), 0U);
}

}  // namespace
}  // namespace node
}  // namespace mrs_vpr
