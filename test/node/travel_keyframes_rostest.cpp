// Drives the node of travel_keyframes.test: the robot's pose on /tf and a camera frame at each pose.
// With ~min_travel 1 m, a frame becomes a keyframe each metre; a stop adds none, a frame whose pose
// is unknown is skipped and counted while the node runs on, and after ~reset the next frame is kept
// wherever it is.

#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <vector>

#include <ros/ros.h>
#include <rosgraph_msgs/Log.h>
#include <sensor_msgs/Image.h>
#include <std_srvs/Trigger.h>
#include <tf2_msgs/TFMessage.h>

#include "mrs_vpr/MapInfo.h"
#include "support/image_message.hpp"
#include "support/map_info_watch.hpp"
#include "support/rostest_main.hpp"
#include "support/route_fixture.hpp"
#include "support/service_call.hpp"
#include "support/subscriber_wait.hpp"
#include "support/topic_inbox.hpp"
#include "support/travel_drive.hpp"

namespace {

constexpr double kFramePeriod = 0.05;  // [s]
constexpr double kStart = 1000.0;      // stamp of the first frame [s]
const char* const kNode = "mrs_vpr_travel";

using mrs_vpr::testing_support::imageMessage;
using mrs_vpr::testing_support::MapInfoWatch;
using mrs_vpr::testing_support::waitForSubscribers;

/// The robot at x metres along odom's x axis, at `stamp`.
tf2_msgs::TFMessage poseAt(double x, double stamp) {
  tf2_msgs::TFMessage message;
  message.transforms.push_back(mrs_vpr::testing_support::transformAt(ros::Time(stamp), "odom", "base_link", x));
  return message;
}

TEST(TravelKeyframes, AFrameEachMetreAndNoneWhileTheRobotStandsStill) {
  ros::NodeHandle nh;
  MapInfoWatch map_info(nh, std::string("/") + kNode);
  ros::Publisher tf_pub = nh.advertise<tf2_msgs::TFMessage>("/tf", 1000);
  ros::Publisher image_pub = nh.advertise<sensor_msgs::Image>("camera/image", 1000);
  // Both nodes of travel_keyframes.test listen to /tf: one connected listener may be the other node's,
  // and poses sent before this node's listener connects never reach it.
  ASSERT_TRUE(waitForSubscribers(tf_pub, 2, 30.0));
  ASSERT_TRUE(waitForSubscribers(image_pub, 1, 30.0));

  // Driving 4 m at 0.25 m a frame, standing still for 30 frames (odometry jitters by 1 cm), then
  // driving 2 m at 0.5 m a frame: keyframes at 0, 1, 2, 3, 4, 5 and 6 m.
  const std::vector<double> positions = mrs_vpr::testing_support::driveStopDrive();
  const std::vector<cv::Mat> frames =
      mrs_vpr::testing_support::shortRouteImages(static_cast<int>(positions.size()));

  for (std::size_t i = 0; i < positions.size(); ++i) {
    const double stamp = kStart + static_cast<double>(i) * kFramePeriod;
    tf_pub.publish(poseAt(positions[i], stamp));
    image_pub.publish(imageMessage(frames[i], stamp));
  }
  const auto total = static_cast<std::uint64_t>(positions.size());
  ASSERT_TRUE(map_info.waitFor([&](const mrs_vpr::MapInfo& info) { return info.frames_received == total; }, 60.0))
      << "received " << map_info.latest().frames_received << " of " << total;
  // Received is not yet processed: each frame may wait up to ~tf_timeout for its pose.
  ASSERT_TRUE(map_info.waitFor([](const mrs_vpr::MapInfo& info) { return info.frames == 7; }, 60.0))
      << "map frames: " << map_info.latest().frames << ", without pose: " << map_info.latest().frames_without_pose
      << ", skipped: " << map_info.latest().frames_skipped;
  const mrs_vpr::MapInfo driven = map_info.latest();
  EXPECT_EQ(driven.frames_skipped, total - 7);
  EXPECT_EQ(driven.frames_without_pose, 0U);
  EXPECT_EQ(driven.frames_failed, 0U);

  // A frame stamped long before any pose: skipped and counted, the map unchanged, the node alive.
  image_pub.publish(imageMessage(frames[0], kStart - 100.0));
  ASSERT_TRUE(map_info.waitFor([](const mrs_vpr::MapInfo& info) { return info.frames_without_pose == 1; }, 30.0))
      << "frames without pose: " << map_info.latest().frames_without_pose;
  EXPECT_EQ(map_info.latest().frames, 7U);

  // Driving on keeps adding keyframes.
  double stamp = kStart + static_cast<double>(positions.size()) * kFramePeriod;
  tf_pub.publish(poseAt(7.0, stamp));
  image_pub.publish(imageMessage(frames[1], stamp));
  ASSERT_TRUE(map_info.waitFor([](const mrs_vpr::MapInfo& info) { return info.frames == 8; }, 30.0))
      << "map frames: " << map_info.latest().frames;

  // After ~reset the map starts again from the next frame, only 0.1 m from the last keyframe.
  std_srvs::Trigger reset;
  ASSERT_TRUE(mrs_vpr::testing_support::callService(std::string("/") + kNode + "/reset", reset));
  ASSERT_TRUE(reset.response.success) << reset.response.message;
  stamp += kFramePeriod;
  tf_pub.publish(poseAt(7.1, stamp));
  image_pub.publish(imageMessage(frames[2], stamp));
  EXPECT_TRUE(map_info.waitFor([](const mrs_vpr::MapInfo& info) { return info.frames == 1; }, 30.0))
      << "map frames after the reset: " << map_info.latest().frames;
}

TEST(TravelKeyframes, FramesFailAtOnceNamingAnOdometryFrameThatNothingPublishes) {
  ros::NodeHandle nh;
  const std::string node = "/mrs_vpr_no_odometry";
  MapInfoWatch map_info(nh, node);
  mrs_vpr::testing_support::TopicInbox<rosgraph_msgs::Log> log(nh, "/rosout");
  ros::Publisher image_pub = nh.advertise<sensor_msgs::Image>("untracked_camera/image", 100);
  ASSERT_TRUE(waitForSubscribers(image_pub, 1, 30.0));
  const std::vector<cv::Mat> frames = mrs_vpr::testing_support::shortRouteImages(20);

  // ~tf_timeout is 5 s: waiting that long for each frame, 20 frames would take 100 s.
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < frames.size(); ++i) {
    image_pub.publish(imageMessage(frames[i], kStart + static_cast<double>(i) * kFramePeriod));
  }
  ASSERT_TRUE(map_info.waitFor([](const mrs_vpr::MapInfo& info) { return info.frames_without_pose == 20; }, 60.0))
      << "frames without pose: " << map_info.latest().frames_without_pose;
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(elapsed, 20.0) << "one wait of ~tf_timeout, then none";
  const mrs_vpr::MapInfo info = map_info.latest();
  EXPECT_EQ(info.frames_received, 20U);
  EXPECT_EQ(info.frames_failed, 0U) << "frames were lost from the queue";
  EXPECT_EQ(info.frames, 0U);
  rosgraph_msgs::Log warning;
  EXPECT_TRUE(log.waitFor(
      [&](const rosgraph_msgs::Log& message) {
        return message.name == node && message.msg.find("frame 'unpublished_odom' does not exist") != std::string::npos;
      },
      warning, 10.0))
      << "no warning names the missing frame";
}

}  // namespace

int main(int argc, char** argv) {
  return mrs_vpr::testing_support::runRostests(argc, argv, "mrs_vpr_travel_keyframes_rostest");
}
