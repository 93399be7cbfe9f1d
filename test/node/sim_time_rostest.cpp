// The node under use_sim_time with no /clock (see sim_time.test): ROS time stands at 0, and timers on
// ROS time would never fire. ~map_info must still report the map, and continuous mode still answer.

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include <ros/ros.h>

#include "mrs_vpr/LoopClosure.h"
#include "support/image_message.hpp"
#include "support/map_info_watch.hpp"
#include "support/rostest_main.hpp"
#include "support/route_fixture.hpp"
#include "support/subscriber_wait.hpp"
#include "support/topic_inbox.hpp"

namespace {

using mrs_vpr::testing_support::defaultRouteImages;

TEST(SimulatedTime, WithoutAClockTheMapIsReportedAndContinuousModeAnswers) {
  ros::NodeHandle nh;
  ASSERT_TRUE(ros::Time::isSimTime());
  ASSERT_TRUE(ros::Time::now().isZero()) << "a /clock runs: the test needs ROS time standing at 0";
  ros::Publisher images = nh.advertise<sensor_msgs::Image>("camera/image", 1000);
  mrs_vpr::testing_support::MapInfoWatch map_info(nh, "mrs_vpr");
  mrs_vpr::testing_support::TopicInbox<mrs_vpr::LoopClosure> closures(nh, "mrs_vpr/loop_closure");
  ASSERT_TRUE(closures.waitConnected(30.0));
  ASSERT_TRUE(mrs_vpr::testing_support::waitForSubscribers(images, 1, 30.0));
  // Stamped as a recording is: the stamps, not ROS time, place the frames.
  const std::vector<cv::Mat>& reference = defaultRouteImages().reference;
  constexpr std::uint32_t kFrames = 150;
  for (std::uint32_t i = 0; i < kFrames; ++i) {
    images.publish(mrs_vpr::testing_support::imageMessage(reference[i], 1000.0 + 0.1 * i));
    ros::WallDuration(0.002).sleep();
  }
  EXPECT_TRUE(map_info.waitFor([](const mrs_vpr::MapInfo& m) { return m.frames == kFrames; }, 30.0))
      << "~map_info says " << map_info.latest().frames << " frames";
  const std::vector<mrs_vpr::LoopClosure> answered = closures.waitForCount(1, 30.0);
  ASSERT_FALSE(answered.empty()) << "continuous mode never answered";
  EXPECT_GT(answered.front().header.stamp.toSec(), 1000.0);  // a frame's stamp, not ROS time
}

// A camera that leaves its stamps 0 gets its frames' arrival times, which before the first /clock are 0
// too: such frames are dropped and counted, not mapped at no time (every closure to them would name 0).
TEST(SimulatedTime, AFrameOfNoStampBeforeTheClockIsDroppedAndCounted) {
  ros::NodeHandle nh;
  ASSERT_TRUE(ros::Time::now().isZero()) << "a /clock runs: the test needs ROS time standing at 0";
  ros::Publisher images = nh.advertise<sensor_msgs::Image>("camera/image", 1000);
  mrs_vpr::testing_support::MapInfoWatch map_info(nh, "mrs_vpr");
  ASSERT_TRUE(mrs_vpr::testing_support::waitForSubscribers(images, 1, 30.0));
  ASSERT_TRUE(map_info.waitFor([](const mrs_vpr::MapInfo& m) { return m.frames > 0; }, 30.0));
  const mrs_vpr::MapInfo before = map_info.latest();
  const std::vector<cv::Mat>& query = defaultRouteImages().query;
  constexpr std::uint64_t kUnstamped = 5;
  for (std::uint64_t i = 0; i < kUnstamped; ++i) {
    images.publish(mrs_vpr::testing_support::imageMessage(query[200 + 10 * i], 0.0));
    ros::WallDuration(0.002).sleep();
  }
  EXPECT_TRUE(map_info.waitFor(
      [&](const mrs_vpr::MapInfo& m) { return m.frames_failed == before.frames_failed + kUnstamped; }, 30.0))
      << "~map_info counts " << map_info.latest().frames_failed << " failed frames";
  EXPECT_EQ(map_info.latest().frames, before.frames);
  EXPECT_EQ(map_info.latest().frames_received, before.frames_received + kUnstamped);
}

}  // namespace

int main(int argc, char** argv) { return mrs_vpr::testing_support::runRostests(argc, argv, "sim_time_test"); }
