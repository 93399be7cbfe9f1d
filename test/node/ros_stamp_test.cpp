#include <gtest/gtest.h>

#include <stdexcept>

#include "mrs_vpr/node/ros_stamp.hpp"

namespace mrs_vpr {
namespace node {
namespace {

TEST(RosStamp, EveryRosTimeConvertsExactlyBothWays) {
  for (const ros::Time& time : {ros::Time(), ros::Time(1700000000U, 123456789U), ros::Time(4294967295U, 999999999U)}) {
    const Stamp stamp = stampOf(time);
    EXPECT_EQ(stamp.nanoseconds(), static_cast<std::int64_t>(time.toNSec()));
    EXPECT_EQ(rosTimeOf(stamp), time);
  }
  EXPECT_EQ(stampOf(ros::Time(4294967295U, 999999999U)).nanoseconds(), Stamp::kMaxNanoseconds);
}

TEST(RosStamp, AnUnnormalisedTimeIsSummedOrRefusedBeyondTheRange) {
  ros::Time unnormalised;  // As a message may carry it: ros::Time's constructor would normalise it.
  unnormalised.sec = 10;
  unnormalised.nsec = 2500000000U;
  EXPECT_EQ(stampOf(unnormalised), Stamp::fromSecondsAndNanoseconds(12U, 500000000U));
  unnormalised.sec = 4294967295U;
  unnormalised.nsec = 1999999999U;
  EXPECT_THROW(stampOf(unnormalised), std::invalid_argument);
}

}  // namespace
}  // namespace node
}  // namespace mrs_vpr
