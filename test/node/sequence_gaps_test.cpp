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

}  // namespace
}  // namespace node
}  // namespace mrs_vpr
