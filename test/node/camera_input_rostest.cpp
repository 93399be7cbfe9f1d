// Drives the nodes of camera_input.test: one route published raw, as JPEG and as PNG (the
// `compressed` transport) and as a Bayer camera's raw mosaics, the answers compared, and bad
// compressed frames counted; bursts of large frames into a one-frame queue, every frame counted; a
// camera throttled by topic_tools, none of its thinning counted as lost; a node whose topic nobody publishes, warning of it, and of a camera that stopped; failed queries,
// each logged.

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <ros/ros.h>
#include <rosgraph_msgs/Log.h>
#include <sensor_msgs/CompressedImage.h>

#include "mrs_vpr/MapInfo.h"
#include "mrs_vpr/QuerySequence.h"
#include "mrs_vpr/synthetic_route.hpp"
#include "node/camera_mosaics.hpp"
#include "support/image_message.hpp"
#include "support/map_info_watch.hpp"
#include "support/rostest_main.hpp"
#include "support/route_fixture.hpp"
#include "support/service_call.hpp"
#include "support/subscriber_wait.hpp"
#include "support/topic_inbox.hpp"

namespace {

constexpr double kFramePeriod = 0.05;  // [s], 20 Hz as in the demo
constexpr int kQueryLength = 80;       // the demo's queries: 80 frames from 60, 120, ..., 300

using mrs_vpr::testing_support::imageMessage;
using mrs_vpr::testing_support::MapInfoWatch;
using mrs_vpr::testing_support::waitForSubscribers;

/// What image_transport's compressed publisher sends for a bgr8 image.
sensor_msgs::CompressedImage toCompressed(const cv::Mat& bgr, double stamp, const std::string& codec) {
  sensor_msgs::CompressedImage message;
  message.header.stamp = ros::Time(stamp);
  message.header.frame_id = "camera";
  message.format = "bgr8; " + codec + " compressed bgr8";
  cv::imencode(codec == "jpeg" ? ".jpg" : ".png", bgr, message.data);
  return message;
}

/// Waits for a message of `level` from `node` on /rosout that starts with `start` and holds `part`.
bool logged(mrs_vpr::testing_support::TopicInbox<rosgraph_msgs::Log>& log, const std::string& node,
            std::uint8_t level, const std::string& start, const std::string& part, double timeout) {
  rosgraph_msgs::Log found;
  return log.waitFor(
      [&](const rosgraph_msgs::Log& m) {
        return m.name == node && m.level == level && m.msg.rfind(start, 0) == 0 &&
               m.msg.find(part) != std::string::npos;
      },
      found, timeout);
}

/// A camera publishing on `topic` into the node `node` ("/mrs_vpr_small_queue"), once the node runs
/// and subscribes to it.
ros::Publisher cameraInto(ros::NodeHandle& nh, const std::string& node, const std::string& topic) {
  EXPECT_TRUE(ros::service::waitForService(node + "/query", ros::Duration(30.0))) << node << " does not run";
  ros::Publisher publisher = nh.advertise<sensor_msgs::Image>(topic, 100);
  EXPECT_TRUE(waitForSubscribers(publisher, 1, 30.0)) << topic << " has no subscriber";
  return publisher;
}

TEST(CameraSilence, ANodeWarnsOfATopicNobodyPublishesOfAPublisherThatSendsNothingAndOfOneThatWent) {
  // The two nodes start 3 s after the test (camera_input.test), and this test runs first, so that their
  // first warnings, 5 s later, come after this subscription to /rosout is connected.
  ros::NodeHandle nh;
  mrs_vpr::testing_support::TopicInbox<rosgraph_msgs::Log> log(nh, "/rosout");
  ros::Publisher idle = nh.advertise<sensor_msgs::Image>("/camera/idle", 10);  // connected, never sends
  EXPECT_TRUE(logged(log, "/mrs_vpr_no_camera", rosgraph_msgs::Log::WARN,
                     "mrs_vpr: no image has arrived on /camera/none in the",
                     "no node publishes it (check the name with `rostopic list`", 30.0))
      << "no warning of a topic nobody publishes";
  EXPECT_TRUE(logged(log, "/mrs_vpr_idle_camera", rosgraph_msgs::Log::WARN,
                     "mrs_vpr: no image has arrived on /camera/idle in the",
                     "1 publisher is connected but sends nothing (check with `rostopic hz /camera/idle`)", 10.0))
      << "no warning of a publisher that sends nothing";

  ros::Publisher camera = nh.advertise<sensor_msgs::Image>("/camera/none", 10);
  ASSERT_TRUE(waitForSubscribers(camera, 1, 30.0));
  const std::vector<cv::Mat> frames = mrs_vpr::testing_support::shortRouteImages(10);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    camera.publish(imageMessage(frames[i], 100.0 + static_cast<double>(i) * kFramePeriod));
    ros::WallDuration(kFramePeriod).sleep();
  }
  EXPECT_TRUE(logged(log, "/mrs_vpr_no_camera", rosgraph_msgs::Log::INFO, "mrs_vpr: images arrive on /camera/none now",
                     "", 10.0));
  // The camera's driver stops: a second silence, reported after twice the first wait.
  camera.shutdown();
  EXPECT_TRUE(logged(log, "/mrs_vpr_no_camera", rosgraph_msgs::Log::WARN,
                     "mrs_vpr: no image has arrived on /camera/none for ",
                     "its publisher has gone (a camera driver that stopped, or a bag that ended)", 20.0))
      << "no warning of a camera that stopped";
}

TEST(FailedQueries, EachKindOfFailedQueryIsLoggedAtOnce) {
  // A user reads a failed call's reason in the node's log as well as in the response: each different
  // mistake is logged at once (a throttle of ROS's hid the second here); the same one made again
  // within a second, also after another, is not, so that a client that alternates does not flood it.
  ros::NodeHandle nh;
  mrs_vpr::testing_support::TopicInbox<rosgraph_msgs::Log> log(nh, "/rosout");
  ASSERT_TRUE(ros::service::waitForService("/mrs_vpr_idle_camera/query", ros::Duration(30.0)));
  ros::ServiceClient query =
      mrs_vpr::testing_support::persistentClient<mrs_vpr::QuerySequence>(nh, "/mrs_vpr_idle_camera/query");
  const auto failuresLogged = [&] {
    int count = 0;
    for (const rosgraph_msgs::Log& m : log.received()) {
      count += m.name == "/mrs_vpr_idle_camera" && m.level == rosgraph_msgs::Log::WARN &&
               m.msg.rfind("mrs_vpr: query failed: ", 0) == 0;
    }
    return count;
  };
  const auto failedCall = [&](const std::string& method) {
    mrs_vpr::QuerySequence call;  // no images and no recent_frames: always refused
    call.request.method = method;
    return query.call(call) && !call.response.success;
  };
  // The node's log reaches this subscription only once connected: call until a failure is seen.
  const ros::WallTime connected_by = ros::WallTime::now() + ros::WallDuration(20.0);
  while (failuresLogged() == 0 && ros::WallTime::now() < connected_by) {
    ASSERT_TRUE(failedCall(""));
    ros::WallDuration(1.5).sleep();
  }
  ASSERT_GT(failuresLogged(), 0) << "no failed query was logged";
  ros::WallDuration(1.5).sleep();  // past any throttle's period
  log.clear();
  for (const std::string method : {"", "no_such_method", ""}) EXPECT_TRUE(failedCall(method)) << method;
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(10.0);
  while (failuresLogged() < 2 && ros::WallTime::now() < deadline) ros::WallDuration(0.05).sleep();
  ros::WallDuration(1.5).sleep();  // and nothing more, however slowly /rosout relays it
  EXPECT_EQ(failuresLogged(), 2);
  ros::WallDuration(1.0).sleep();  // past the second
  EXPECT_TRUE(failedCall(""));
  while (failuresLogged() < 3 && ros::WallTime::now() < deadline + ros::WallDuration(2.0)) {
    ros::WallDuration(0.05).sleep();
  }
  EXPECT_EQ(failuresLogged(), 3);
}

class CompressedTransportTest : public ::testing::Test {
 protected:
  void SetUp() override {
    for (const std::string& node : kNodes) {
      ASSERT_TRUE(ros::service::waitForService(node + "/query", ros::Duration(30.0))) << node;
    }
    if (!mapped_) {
      mapReference();
      mapped_ = true;
    }
  }

  /// Publishes the reference traversal on the four topics and waits until every map holds it.
  void mapReference() {
    ros::Publisher raw = nh_.advertise<sensor_msgs::Image>("/camera/raw", 1000);
    ros::Publisher jpeg = nh_.advertise<sensor_msgs::CompressedImage>("/camera/jpeg/compressed", 1000);
    ros::Publisher png = nh_.advertise<sensor_msgs::CompressedImage>("/camera/png/compressed", 1000);
    ros::Publisher bayer = nh_.advertise<sensor_msgs::Image>("/camera/bayer", 1000);
    for (const ros::Publisher& publisher : {raw, jpeg, png, bayer}) {
      ASSERT_TRUE(waitForSubscribers(publisher, 1, 30.0)) << publisher.getTopic() << " has no subscriber";
    }
    for (std::size_t i = 0; i < route_.reference.size(); ++i) {
      const double stamp = 1000.0 + static_cast<double>(i) * kFramePeriod;
      raw.publish(imageMessage(route_.reference[i], stamp));
      jpeg.publish(toCompressed(route_.reference[i], stamp, "jpeg"));
      png.publish(toCompressed(route_.reference[i], stamp, "png"));
      bayer.publish(bayerMessage(route_.reference[i], stamp));
      ros::WallDuration(0.002).sleep();
    }
    const auto frames = static_cast<std::uint32_t>(route_.reference.size());
    for (const std::string& node : kNodes) {
      MapInfoWatch watch(nh_, node);
      mrs_vpr::MapInfo info;
      ASSERT_TRUE(watch.waitFor(
          [&](const mrs_vpr::MapInfo& m) {
            info = m;
            return m.frames == frames;
          },
          30.0))
          << node << " holds " << info.frames << " frames, not " << frames;
      EXPECT_EQ(info.frames_failed, 0U) << node;
      EXPECT_EQ(info.frames_received, frames) << node;
    }
  }

  /// What a camera with an RGGB colour filter publishes as image_raw for the view `bgr`.
  static sensor_msgs::Image bayerMessage(const cv::Mat& bgr, double stamp) {
    return imageMessage(mrs_vpr::node::testing::mosaicOf(bgr, "rggb"), stamp, "bayer_rggb8");
  }

  /// Asks `node` about kQueryLength query frames from `first`, as bgr8 images or as Bayer mosaics.
  mrs_vpr::QuerySequence::Response query(const std::string& node, int first, const std::string& method,
                                         bool mosaics = false) {
    mrs_vpr::QuerySequence srv;
    for (int i = first; i < first + kQueryLength; ++i) {
      const cv::Mat& frame = route_.query[static_cast<std::size_t>(i)];
      const double stamp = 9000.0 + i * kFramePeriod;
      srv.request.images.push_back(mosaics ? bayerMessage(frame, stamp) : imageMessage(frame, stamp));
    }
    srv.request.method = method;
    EXPECT_TRUE(mrs_vpr::testing_support::callService(node + "/query", srv)) << node;
    return srv.response;
  }

  const std::vector<std::string> kNodes{"/mrs_vpr_raw", "/jpeg/mrs_vpr", "/mrs_vpr_png", "/mrs_vpr_bayer"};
  const mrs_vpr::SyntheticRoute& route_ = mrs_vpr::testing_support::standardRouteImages();
  static bool mapped_;
  ros::NodeHandle nh_;
};

bool CompressedTransportTest::mapped_ = false;

TEST_F(CompressedTransportTest, CompressedMapsGiveTheRawMapsAnswers) {
  for (const int first : {60, 120, 180, 240, 300}) {
    for (const std::string method : {"mrs", "seqslam"}) {
      SCOPED_TRACE(method + " from query frame " + std::to_string(first));
      const auto raw = query("/mrs_vpr_raw", first, method);
      ASSERT_TRUE(raw.success) << raw.message;
      // The first stretch is a guess, not accepted, as in the demo; the others are closures.
      EXPECT_EQ(raw.accepted, first > 60);
      if (raw.accepted) {
        const int truth = route_.query_to_reference[static_cast<std::size_t>(first + kQueryLength - 1)];
        EXPECT_NEAR(raw.reference_index, truth, 5);
      }

      // PNG is lossless: the very same map, so the very same answer.
      const auto png = query("/mrs_vpr_png", first, method);
      ASSERT_TRUE(png.success) << png.message;
      EXPECT_EQ(png.reference_index, raw.reference_index);
      EXPECT_FLOAT_EQ(png.confidence, raw.confidence);
      EXPECT_EQ(png.accepted, raw.accepted);

      // JPEG: the same answer, its confidence within the codec's error.
      const auto jpeg = query("/jpeg/mrs_vpr", first, method);
      ASSERT_TRUE(jpeg.success) << jpeg.message;
      EXPECT_EQ(jpeg.reference_index, raw.reference_index);
      EXPECT_EQ(jpeg.accepted, raw.accepted);
      EXPECT_NEAR(jpeg.confidence, raw.confidence, 0.1 * raw.confidence + 0.5);

      // A Bayer camera's mosaics, mapped and asked about as they come: demosaiced to nearly the
      // same grey, so the same place.
      const auto bayer = query("/mrs_vpr_bayer", first, method, true);
      ASSERT_TRUE(bayer.success) << bayer.message;
      EXPECT_NEAR(bayer.reference_index, raw.reference_index, 2);
      EXPECT_EQ(bayer.accepted, raw.accepted) << "confidence " << bayer.confidence << " against " << raw.confidence;
    }
  }
}

TEST_F(CompressedTransportTest, BadCompressedFramesAreCountedAndTheNodeKeepsMapping) {
  ros::Publisher jpeg = nh_.advertise<sensor_msgs::CompressedImage>("/camera/jpeg/compressed", 100);
  ASSERT_TRUE(waitForSubscribers(jpeg, 1, 30.0)) << "/camera/jpeg/compressed has no subscriber";
  MapInfoWatch watch(nh_, "/jpeg/mrs_vpr");
  mrs_vpr::MapInfo before;
  ASSERT_TRUE(watch.waitFor(
      [&](const mrs_vpr::MapInfo& m) {
        before = m;
        return true;
      },
      30.0));

  const cv::Mat& image = route_.reference[0];
  double stamp = 5000.0;
  std::vector<sensor_msgs::CompressedImage> bad;
  bad.push_back(toCompressed(image, stamp, "jpeg"));
  bad.back().format = "bgr8; tiff compressed bgr8";  // a format the node does not decode
  bad.push_back(toCompressed(image, stamp += 1.0, "jpeg"));
  bad.back().data.resize(bad.back().data.size() / 10);  // corrupt: cut inside the image data
  std::fill(bad.back().data.begin() + 4, bad.back().data.end(), 0x00);
  bad.push_back(toCompressed(image, stamp += 1.0, "png"));
  bad.back().format = "png";
  bad.back().data[16] = 0x7F;  // forged IHDR width of about 2 billion pixels: refused before decoding
  bad.push_back(toCompressed(image, stamp += 1.0, "png"));
  bad.back().format = "jpeg";  // mislabelled
  for (const auto& message : bad) {
    jpeg.publish(message);
  }
  jpeg.publish(toCompressed(image, stamp += 1.0, "jpeg"));  // a good frame after them

  const auto failed = before.frames_failed + bad.size();
  mrs_vpr::MapInfo after;
  ASSERT_TRUE(watch.waitFor(
      [&](const mrs_vpr::MapInfo& m) {
        after = m;
        return m.frames_failed == failed && m.frames == before.frames + 1;
      },
      30.0))
      << "failed " << after.frames_failed << ", frames " << after.frames;
  EXPECT_EQ(after.frames_received, before.frames_received + bad.size() + 1);
  const auto answer = query("/jpeg/mrs_vpr", 120, "mrs");
  EXPECT_TRUE(answer.success) << answer.message;
}

TEST(LostFrames, EveryFrameOfABurstIsCountedEvenWhenTheQueueDropsIt) {
  // 4000 x 3000 frames take tens of milliseconds each to describe; published back to back into a
  // one-frame subscriber queue, most are dropped by roscpp before the callback. Each must still be
  // counted: received, and either mapped or failed.
  ros::NodeHandle nh;
  ros::Publisher publisher = cameraInto(nh, "/mrs_vpr_small_queue", "/camera/burst");
  ASSERT_FALSE(::testing::Test::HasFailure());
  MapInfoWatch watch(nh, "/mrs_vpr_small_queue");
  cv::RNG rng(3);
  std::vector<sensor_msgs::Image> frames;
  for (const cv::Size size : {cv::Size(4000, 3000), cv::Size(640, 480)}) {
    cv::Mat image(size, CV_8UC3);
    rng.fill(image, cv::RNG::UNIFORM, 0, 256);
    frames.push_back(imageMessage(image, 0.0));
  }
  // Three frames, received one by one before the burst: the node counts lost frames from gaps in
  // header.seq, so a frame lost before the first one it receives is no gap it could see, and the
  // first steps of a numbering only teach its usual step (a throttled stream's is more than one).
  int published = 0;
  for (int i = 0; i < 3; ++i) {
    frames[1].header.stamp = ros::Time(97.0 + i);
    publisher.publish(frames[1]);
    ++published;
    ASSERT_TRUE(watch.waitFor(
        [&](const mrs_vpr::MapInfo& m) { return m.frames_received == static_cast<std::uint64_t>(published); },
        30.0));
  }
  for (int i = 0; i < 12; ++i) {  // 6 large frames, and 6 small ones between them
    sensor_msgs::Image& frame = frames[static_cast<std::size_t>(i % 2)];
    frame.header.stamp = ros::Time(100.0 + i);
    publisher.publish(frame);
    ++published;
  }
  ros::WallDuration(1.0).sleep();
  // A last frame after the burst shows the gap before it. Stamped as the recording goes on, a second
  // a frame: a seq jump whose stamps do not match is another recording, not lost frames.
  frames[1].header.stamp = ros::Time(112.0);
  publisher.publish(frames[1]);
  ++published;

  // The node counts a frame as received before it describes it, so a snapshot taken as the last
  // frame arrives can miss it: wait until every received frame is accounted for. A frame that is
  // received and then lost never gets there.
  mrs_vpr::MapInfo info;
  ASSERT_TRUE(watch.waitFor(
      [&](const mrs_vpr::MapInfo& m) {
        info = m;
        return m.frames_received == static_cast<std::uint64_t>(published) &&
               m.frames + m.frames_failed == m.frames_received;
      },
      60.0))
      << "received " << info.frames_received << " of " << published << ", mapped " << info.frames << ", failed "
      << info.frames_failed;
  EXPECT_EQ(info.frames + info.frames_failed, info.frames_received);
  EXPECT_EQ(info.frames_dropped, 0U);
  EXPECT_GE(info.frames, 2U);
  EXPECT_GT(info.frames_failed, 0U) << "the burst lost no frame: the count of lost frames went untested";
}

TEST(LostFrames, ANodeSlowerThanItsCameraCountsEveryFrameItsQueueDrops) {
  // A camera far faster than the node describes its frames: its one-frame queue keeps the newest,
  // so the node sees the camera's seq advance by a steady step, as behind a throttle. Each frame
  // skipped there was lost all the same, and must be counted.
  ros::NodeHandle nh;
  ros::Publisher publisher = cameraInto(nh, "/mrs_vpr_overloaded", "/camera/overload");
  ASSERT_FALSE(::testing::Test::HasFailure());
  MapInfoWatch watch(nh, "/mrs_vpr_overloaded");
  mrs_vpr::MapInfo before;
  ASSERT_TRUE(watch.waitFor(
      [&](const mrs_vpr::MapInfo& m) {
        before = m;
        return m.frames + m.frames_failed == m.frames_received;
      },
      30.0));
  cv::RNG rng(7);
  cv::Mat small(480, 640, CV_8UC3);
  cv::Mat large(3000, 4000, CV_8UC1);
  rng.fill(small, cv::RNG::UNIFORM, 0, 256);
  rng.fill(large, cv::RNG::UNIFORM, 0, 256);
  // Stamped as a 200 Hz camera throughout, so that the stamps bear every seq gap out.
  constexpr double kPeriod = 0.005;
  int published = 0;
  const auto publish = [&](const cv::Mat& image) {
    publisher.publish(imageMessage(image, 1000.0 + kPeriod * published, image.channels() == 1 ? "mono8" : "bgr8"));
    ++published;
  };
  for (int i = 0; i < 3; ++i) {  // one by one: the node keeps up
    publish(small);
    ASSERT_TRUE(watch.waitFor(
        [&](const mrs_vpr::MapInfo& m) { return m.frames_received == before.frames_received + published; }, 30.0));
  }
  ros::Rate camera(1.0 / kPeriod);
  for (int i = 0; i < 40; ++i) {  // each takes the node several periods to describe
    publish(large);
    camera.sleep();
  }
  ros::WallDuration(1.0).sleep();
  publish(small);  // shows the gap before it
  mrs_vpr::MapInfo after;
  ASSERT_TRUE(watch.waitFor(
      [&](const mrs_vpr::MapInfo& m) {
        after = m;
        return m.frames_received == before.frames_received + published &&
               m.frames + m.frames_failed == m.frames_received;
      },
      60.0))
      << "received " << after.frames_received - before.frames_received << " of " << published << ", mapped "
      << after.frames - before.frames << ", failed " << after.frames_failed - before.frames_failed;
  EXPECT_GE(after.frames_failed - before.frames_failed, 3U)
      << "the node kept up: the test tested nothing (received " << after.frames_received - before.frames_received
      << " of " << published << ", failed " << after.frames_failed - before.frames_failed << ")";
}

TEST(LostFrames, ACameraThrottledOnPurposeLosesNoFrame) {
  // topic_tools throttle passes the camera's header.seq on, so a 30 Hz camera thinned to 10 Hz
  // arrives 3 or 4 seqs a message. Each of those steps counted 2 or 3 lost frames, with a warning
  // that blamed the node's queue.
  ros::NodeHandle nh;
  ros::Publisher camera = cameraInto(nh, "/mrs_vpr_throttled", "/camera/fast");  // through the throttle
  ASSERT_FALSE(::testing::Test::HasFailure());
  mrs_vpr::testing_support::TopicInbox<sensor_msgs::Image> throttled(nh, "/camera/throttled");
  MapInfoWatch watch(nh, "/mrs_vpr_throttled");
  cv::RNG rng(5);
  ros::Rate rate(30.0);
  const int published = 120;
  for (int i = 0; i < published; ++i) {
    cv::Mat image(48, 64, CV_8UC3);
    rng.fill(image, cv::RNG::UNIFORM, 0, 256);
    camera.publish(imageMessage(image, 100.0 + i / 30.0));
    rate.sleep();
  }
  ros::WallDuration(1.0).sleep();
  // The throttle advertises its output with the first frame it forwards, so its first frame or two
  // may reach this test and not the node, or the node and not this test.
  const std::vector<sensor_msgs::Image> forwarded = throttled.messages();
  ASSERT_GE(forwarded.size(), 20U) << "the throttle forwarded too few frames to judge";
  ASSERT_LE(forwarded.size(), 60U) << "the throttle did not thin the stream";
  ASSERT_GE(forwarded.back().header.seq - forwarded.front().header.seq, 2 * (forwarded.size() - 1))
      << "the throttle renumbered the frames: nothing to test";
  mrs_vpr::MapInfo info;
  ASSERT_TRUE(watch.waitFor(
      [&](const mrs_vpr::MapInfo& m) {
        info = m;
        return m.frames_received + 2U >= forwarded.size() && m.frames + m.frames_failed == m.frames_received;
      },
      30.0))
      << "received " << info.frames_received << ", mapped " << info.frames << ", failed " << info.frames_failed
      << "; the test received " << forwarded.size();
  EXPECT_EQ(info.frames_failed, 0U) << "a throttled stream's skipped seqs were counted as lost frames";
  EXPECT_LE(info.frames_received, forwarded.size() + 2U);
}

}  // namespace

int main(int argc, char** argv) {
  return mrs_vpr::testing_support::runRostests(argc, argv, "mrs_vpr_camera_input_rostest");
}
