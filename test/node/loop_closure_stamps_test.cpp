#include <gtest/gtest.h>

#include <string>

#include "mrs_vpr/node/loop_closure_stamps.hpp"

namespace mrs_vpr {
namespace node {
namespace {

/// An accepted closure: the localised test frame at `newest`, reference frame 42 at `reference`.
LoopClosure acceptedClosure(const ros::Time& newest, const ros::Time& reference) {
  LoopClosure closure;
  closure.header.stamp = newest;
  closure.localised_keyframe_stamp = newest;
  closure.header.frame_id = "camera";
  closure.reference_index = 42;
  closure.reference_stamp = reference;
  closure.accepted = true;
  return closure;
}

TEST(LoopClosureStamps, AnAcceptedClosureIsTheNewestTestStampThenTheReferenceStamp) {
  // A realistic Unix time: data[0] is the current frame for LIO-SAM, data[1] the earlier one.
  const ros::Time newest(1700000123, 456789000);
  const ros::Time reference(1700000001, 250000000);
  std::string why;
  const auto stamps = loopClosureStamps(acceptedClosure(newest, reference), why);
  ASSERT_TRUE(stamps.has_value()) << why;
  EXPECT_TRUE(why.empty());
  ASSERT_EQ(stamps->data.size(), 2U);
  EXPECT_EQ(stamps->data[0], newest.toSec());
  EXPECT_EQ(stamps->data[1], reference.toSec());
  EXPECT_NEAR(stamps->data[0], 1700000123.456789, 1e-6);
  EXPECT_NEAR(stamps->data[1], 1700000001.25, 1e-6);
  EXPECT_TRUE(stamps->layout.dim.empty());  // a plain pair, as LIO-SAM's own publishers send it
}

TEST(LoopClosureStamps, AnswersThatAreNotAcceptedGiveNothing) {
  LoopClosure not_accepted = acceptedClosure(ros::Time(2000.0), ros::Time(1000.0));
  not_accepted.accepted = false;
  LoopClosure no_match = acceptedClosure(ros::Time(2000.0), ros::Time());
  no_match.reference_index = -1;
  for (const LoopClosure& closure : {not_accepted, no_match}) {
    std::string why;
    EXPECT_FALSE(loopClosureStamps(closure, why).has_value());
    EXPECT_TRUE(why.empty()) << why;  // nothing wrong: there is simply no closure
  }
}

TEST(LoopClosureStamps, AClosureRestatedForAStoppedFrameGivesNothing) {
  // LIO-SAM would pair it with the keyframe that the closure of its keyframe already closed.
  LoopClosure restated = acceptedClosure(ros::Time(2003.0), ros::Time(1000.0));
  restated.localised_keyframe_stamp = ros::Time(2000.0);
  std::string why;
  EXPECT_FALSE(loopClosureStamps(restated, why).has_value());
  EXPECT_TRUE(why.empty()) << why;
}

TEST(LoopClosureStamps, AnAcceptedClosureWithoutAStampIsRefusedAndSaysWhich) {
  std::string why;
  EXPECT_FALSE(loopClosureStamps(acceptedClosure(ros::Time(), ros::Time(1000.0)), why).has_value());
  EXPECT_EQ(why, "the localised test frame has no stamp");

  why.clear();
  EXPECT_FALSE(loopClosureStamps(acceptedClosure(ros::Time(2000.0), ros::Time()), why).has_value());
  EXPECT_EQ(why, "reference frame 42 has no stamp");
}

}  // namespace
}  // namespace node
}  // namespace mrs_vpr
