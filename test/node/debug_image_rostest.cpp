// ~debug_image of a running mrs_vpr_node (see debug_image.test): drawn for each answered query while
// someone subscribes, and not at all otherwise.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <cv_bridge/cv_bridge.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>

#include "mrs_vpr/MapInfo.h"
#include "mrs_vpr/QuerySequence.h"
#include "mrs_vpr/synthetic_route.hpp"
#include "mrs_vpr/visualization/match_image.hpp"
#include "support/image_message.hpp"
#include "support/map_info_watch.hpp"
#include "support/rostest_main.hpp"
#include "support/route_fixture.hpp"
#include "support/service_call.hpp"
#include "support/subscriber_wait.hpp"
#include "support/topic_inbox.hpp"

namespace {

using mrs_vpr::testing_support::imageMessage;
using mrs_vpr::testing_support::TopicInbox;

constexpr double kFramePeriod = 0.1;  // [s]

class DebugImageTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(ros::service::waitForService("mrs_vpr_debug/query", ros::Duration(30.0)));
    query_ = mrs_vpr::testing_support::persistentClient<mrs_vpr::QuerySequence>(nh_, "mrs_vpr_debug/query");
    if (!mapped_) {
      ros::Publisher images = nh_.advertise<sensor_msgs::Image>("camera/image", 1000);
      ASSERT_TRUE(mrs_vpr::testing_support::waitForSubscribers(images, 1, 20.0));
      for (std::size_t i = 0; i < route_.reference.size(); ++i) {
        images.publish(imageMessage(route_.reference[i], 1000.0 + static_cast<double>(i) * kFramePeriod));
        ros::WallDuration(0.002).sleep();
      }
      ASSERT_TRUE(map_info_.waitFor([](const mrs_vpr::MapInfo& m) { return m.frames == 400; }, 20.0));
      mapped_ = true;
    }
  }

  /// The newest ~map_info, after waiting `settle` seconds for a change to be republished (20 Hz).
  mrs_vpr::MapInfo latestMapInfo(double settle = 0.5) {
    ros::WallDuration(settle).sleep();
    map_info_.waitFor([](const mrs_vpr::MapInfo&) { return true; }, 10.0);
    return map_info_.latest();
  }

  /// Query frames [first, first + count) as an explicit test sequence; the call must succeed.
  mrs_vpr::QuerySequence::Response query(int first, int count, const std::string& method) {
    mrs_vpr::QuerySequence srv;
    for (int i = first; i < first + count; ++i) {
      srv.request.images.push_back(imageMessage(route_.query[static_cast<std::size_t>(i)], 9000.0 + i * kFramePeriod));
    }
    srv.request.method = method;
    EXPECT_TRUE(query_.call(srv)) << "the service call itself failed";
    EXPECT_TRUE(srv.response.success) << srv.response.message;
    return srv.response;
  }

  const mrs_vpr::SyntheticRoute& route_ = mrs_vpr::testing_support::defaultRouteImages();
  static bool mapped_;

  ros::NodeHandle nh_;
  ros::ServiceClient query_;
  mrs_vpr::testing_support::MapInfoWatch map_info_{nh_, "mrs_vpr_debug"};
};

bool DebugImageTest::mapped_ = false;

// The tests run in this order (gtest keeps declaration order) and share the node.

TEST_F(DebugImageTest, NothingIsDrawnWithoutASubscriber) {
  query(100, 40, "mrs");
  query(100, 200, "mrs");
  query(100, 40, "seqslam");
  mrs_vpr::QuerySequence recent;
  recent.request.recent_frames = 40;
  ASSERT_TRUE(query_.call(recent));
  EXPECT_TRUE(recent.response.success) << recent.response.message;
  const mrs_vpr::MapInfo info = latestMapInfo();
  EXPECT_EQ(info.frames, 400U);
  EXPECT_EQ(info.debug_images, 0U);
}

TEST_F(DebugImageTest, ASubscriberGetsOneImagePerAnswer) {
  TopicInbox<sensor_msgs::Image> images(nh_, "mrs_vpr_debug/debug_image");
  ASSERT_TRUE(images.waitConnected());
  ros::WallDuration(0.3).sleep();  // the node's side of the connection, which it counts, may lag ours

  // 200 frames: MRS keeps one coarser level (stride 2) above full resolution (mrs/min_coarse_frames 64).
  query(100, 200, "mrs");
  const auto seqslam = query(100, 40, "seqslam");
  const std::vector<sensor_msgs::Image> received = images.waitForCount(2);
  ASSERT_EQ(received.size(), 2U);

  const cv::Size mrs_size = mrs_vpr::visualization::matchImageLayout(2).size;
  EXPECT_EQ(received[0].encoding, "bgr8");
  EXPECT_EQ(received[0].width, static_cast<std::uint32_t>(mrs_size.width));
  EXPECT_EQ(received[0].height, static_cast<std::uint32_t>(mrs_size.height));
  EXPECT_EQ(received[0].header.stamp, ros::Time(9000.0 + 299 * kFramePeriod));  // the newest test frame
  EXPECT_EQ(received[0].header.frame_id, "camera");
  const cv::Size seqslam_size = mrs_vpr::visualization::matchImageLayout(0).size;
  EXPECT_EQ(received[1].width, static_cast<std::uint32_t>(seqslam_size.width));
  EXPECT_EQ(received[1].height, static_cast<std::uint32_t>(seqslam_size.height));

  // The trajectory (red) is drawn where the answer lies: its last point is in the band.
  const cv::Mat picture = cv_bridge::toCvCopy(received[1], "bgr8")->image;
  int red = 0;
  const cv::Rect band = mrs_vpr::visualization::matchImageLayout(0).band;
  for (int y = band.y; y < band.br().y; ++y) {
    for (int x = band.x; x < band.br().x; ++x) {
      if (picture.at<cv::Vec3b>(y, x) == cv::Vec3b(0, 0, 255)) ++red;
    }
  }
  EXPECT_GT(red, band.height / 4) << "the dashed trajectory should cross the band from top to bottom";
  EXPECT_TRUE(seqslam.accepted);

  EXPECT_TRUE(map_info_.waitFor([](const mrs_vpr::MapInfo& m) { return m.debug_images == 2; }, 20.0))
      << "~map_info should count the two images drawn";

  // Once the subscriber leaves, drawing stops again.
  images.shutdown();
  ros::WallDuration(0.5).sleep();
  query(100, 40, "mrs");
  EXPECT_EQ(latestMapInfo().debug_images, 2U);
}

}  // namespace

int main(int argc, char** argv) {
  return mrs_vpr::testing_support::runRostests(argc, argv, "mrs_vpr_debug_image_rostest");
}
