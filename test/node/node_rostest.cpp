// Drives two running mrs_vpr_node instances (see mrs_vpr_node.test) through their topics and services.

#include <gtest/gtest.h>

#include <sys/wait.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include <ros/ros.h>
#include <std_srvs/Trigger.h>

#include "mrs_vpr/LoopClosure.h"
#include "mrs_vpr/MapInfo.h"
#include "mrs_vpr/QuerySequence.h"
#include "mrs_vpr/synthetic_route.hpp"
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

constexpr int kTolerance = 5;          // frames
constexpr double kReferenceStart = 1000.0;  // stamp of reference frame 0 [s]
constexpr double kQueryStart = 5000.0;      // stamp of the first query frame played into the map [s]
constexpr double kFramePeriod = 0.1;        // [s]

class NodeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(ros::service::waitForService("mrs_vpr/query", ros::Duration(30.0)));
    ASSERT_TRUE(ros::service::waitForService("mrs_vpr_auto/query", ros::Duration(30.0)));
    image_pub_ = nh_.advertise<sensor_msgs::Image>("camera/image", 1000);
    query_ = mrs_vpr::testing_support::persistentClient<mrs_vpr::QuerySequence>(nh_, "mrs_vpr/query");
    if (!reference_published_) {
      playIntoNodes(route_.reference, 0, static_cast<int>(route_.reference.size()), kReferenceStart);
      reference_published_ = true;
    }
    ASSERT_TRUE(loop_closures_.waitConnected());
    ASSERT_TRUE(auto_loop_closures_.waitConnected());
  }

  /// Publishes frames [begin, end) of `frames` stamped start + i * period and waits until both nodes
  /// have added them to their maps.
  void playIntoNodes(const std::vector<cv::Mat>& frames, int begin, int end, double start) {
    // Each test advertises the camera topic anew: wait until both nodes have connected to it.
    ASSERT_TRUE(mrs_vpr::testing_support::waitForSubscribers(image_pub_, 2, 20.0));
    for (int i = begin; i < end; ++i) {
      image_pub_.publish(imageMessage(frames[static_cast<std::size_t>(i)], start + (i - begin) * kFramePeriod));
      ros::WallDuration(0.002).sleep();
    }
    map_frames_ += static_cast<std::uint32_t>(end - begin);
    const std::uint32_t expected = map_frames_;
    mrs_vpr::MapInfo info;
    ASSERT_TRUE(map_info_.waitFor(
        [&](const mrs_vpr::MapInfo& m) {
          info = m;
          return m.frames == expected;
        },
        20.0))
        << "the map did not reach " << expected << " frames";
    EXPECT_EQ(info.descriptor_size, 2048U);  // The 64 x 32 thumbnail the .test file chooses for the route.
    EXPECT_EQ(info.frames_failed, 0U);
    EXPECT_EQ(info.frames_dropped, 0U);
    EXPECT_GT(info.memory_bytes, static_cast<std::uint64_t>(expected) * 2048U - 1U);
    ASSERT_TRUE(auto_map_info_.waitFor([&](const mrs_vpr::MapInfo& m) { return m.frames == expected; }, 20.0));
  }

  /// The explicit test sequence: query frames [first, first + count).
  mrs_vpr::QuerySequence explicitQuery(int first, int count, const std::string& method) const {
    mrs_vpr::QuerySequence srv;
    for (int i = first; i < first + count; ++i) {
      srv.request.images.push_back(imageMessage(route_.query[static_cast<std::size_t>(i)], 9000.0 + i * kFramePeriod));
    }
    srv.request.method = method;
    return srv;
  }

  /// Calls ~query; the call itself must always succeed (failures are in the response).
  mrs_vpr::QuerySequence::Response call(mrs_vpr::QuerySequence& srv) {
    EXPECT_TRUE(query_.call(srv)) << "the service call itself failed";
    return srv.response;
  }

  void expectFailure(mrs_vpr::QuerySequence srv, const std::string& expected_text) {
    const auto response = call(srv);
    EXPECT_FALSE(response.success);
    EXPECT_NE(response.message.find(expected_text), std::string::npos)
        << "message '" << response.message << "' does not name '" << expected_text << "'";
    EXPECT_EQ(response.reference_index, -1);
  }

  const mrs_vpr::SyntheticRoute& route_ = mrs_vpr::testing_support::defaultRouteImages();
  static bool reference_published_;
  static std::uint32_t map_frames_;

  ros::NodeHandle nh_;
  ros::Publisher image_pub_;
  ros::ServiceClient query_;
  mrs_vpr::testing_support::MapInfoWatch map_info_{nh_, "mrs_vpr"};
  mrs_vpr::testing_support::MapInfoWatch auto_map_info_{nh_, "mrs_vpr_auto"};
  TopicInbox<mrs_vpr::LoopClosure> loop_closures_{nh_, "mrs_vpr/loop_closure"};
  TopicInbox<mrs_vpr::LoopClosure> auto_loop_closures_{nh_, "mrs_vpr_auto/loop_closure"};
};

bool NodeTest::reference_published_ = false;
std::uint32_t NodeTest::map_frames_ = 0;

// The tests run in this order (gtest keeps declaration order) and share the nodes' maps.

TEST_F(NodeTest, ExplicitImagesWithBothMethods) {
  const int first = 100;
  const int count = 40;
  const int truth = route_.query_to_reference[first + count - 1];
  for (const std::string method : {"", "mrs", "seqslam"}) {
    SCOPED_TRACE("method '" + method + "'");
    loop_closures_.clear();
    auto srv = explicitQuery(first, count, method);
    const auto response = call(srv);
    ASSERT_TRUE(response.success) << response.message;
    EXPECT_NEAR(response.reference_index, truth, kTolerance);
    EXPECT_NEAR(response.reference_stamp.toSec(), kReferenceStart + response.reference_index * kFramePeriod, 1e-3);
    // A stretch of the mapped route: distinct, so accepted (config/default.yaml: sequence/accept_threshold 3).
    EXPECT_GE(response.confidence, 3.0F);
    EXPECT_TRUE(response.accepted) << response.message;
    EXPECT_GT(response.elapsed_ms, 0.0F);
    EXPECT_EQ(response.threads, 3U);  // place_recognition_node.test: ~threads 3

    const std::string expected_method = method.empty() ? "mrs" : method;
    EXPECT_EQ(response.method, expected_method);
    EXPECT_EQ(response.query_length, static_cast<std::uint32_t>(count));
    mrs_vpr::LoopClosure closure;
    ASSERT_TRUE(loop_closures_.waitFor([](const mrs_vpr::LoopClosure&) { return true; }, closure, 5.0));
    EXPECT_EQ(closure.reference_index, response.reference_index);
    EXPECT_EQ(closure.reference_stamp, response.reference_stamp);
    EXPECT_EQ(closure.query_length, static_cast<std::uint32_t>(count));
    EXPECT_EQ(closure.method, expected_method);
    EXPECT_EQ(closure.accepted, response.accepted);
    EXPECT_FLOAT_EQ(closure.confidence, response.confidence);
    EXPECT_EQ(closure.header.stamp, srv.request.images.back().header.stamp);
    EXPECT_EQ(response.localised_stamp, closure.header.stamp);  // The frame the answer places.
    EXPECT_EQ(closure.header.frame_id, "camera");
  }
}

TEST_F(NodeTest, PlacesNotInTheMapAreAnsweredButNotAccepted) {
  // A route generated from another seed (none of its places is mapped) and uniform noise: the search
  // still has a best end, but it does not stand out from the query's own costs.
  const mrs_vpr::SyntheticRoute& unmapped = mrs_vpr::testing_support::unmappedRouteImages();
  cv::RNG noise(99);
  std::vector<std::pair<std::string, std::vector<cv::Mat>>> sequences{
      {"unmapped route", {unmapped.query.begin() + 100, unmapped.query.begin() + 140}}, {"noise", {}}};
  for (int i = 0; i < 10; ++i) {
    cv::Mat image(64, 128, CV_8UC1);
    noise.fill(image, cv::RNG::UNIFORM, 0, 256);
    sequences[1].second.push_back(image);
  }

  double stamp = 20000.0;  // Stamps of their own, so each query's loop closure can be told apart.
  for (const auto& [name, images] : sequences) {
    for (const std::string method : {"", "mrs", "seqslam"}) {
      SCOPED_TRACE(name + ", method '" + method + "'");
      mrs_vpr::QuerySequence srv;
      for (const cv::Mat& image : images) {
        srv.request.images.push_back(imageMessage(image, stamp, image.channels() == 1 ? "mono8" : "bgr8"));
        stamp += kFramePeriod;
      }
      srv.request.method = method;
      const auto response = call(srv);
      ASSERT_TRUE(response.success) << response.message;
      EXPECT_FALSE(response.accepted) << "confidence " << response.confidence;

      const ros::Time newest = srv.request.images.back().header.stamp;
      mrs_vpr::LoopClosure closure;
      ASSERT_TRUE(loop_closures_.waitFor([&](const mrs_vpr::LoopClosure& m) { return m.header.stamp == newest; },
                                         closure, 5.0));
      EXPECT_FALSE(closure.accepted);
      EXPECT_EQ(closure.reference_index, response.reference_index);
      EXPECT_FLOAT_EQ(closure.confidence, response.confidence);
      EXPECT_EQ(closure.query_length, static_cast<std::uint32_t>(images.size()));
      EXPECT_EQ(closure.method, method.empty() ? "mrs" : method);
    }
  }
}

TEST_F(NodeTest, BadRequestsAreReportedAndTheNodeKeepsServing) {
  expectFailure(mrs_vpr::QuerySequence{}, "empty request");

  auto unknown = explicitQuery(100, 20, "fast");
  expectFailure(unknown, "unknown method 'fast'");
  // Said before any image is converted or described: an image that cannot be read is not the first problem.
  unknown.request.images[0].encoding = "no_such_encoding";
  expectFailure(unknown, "unknown method 'fast'");

  mrs_vpr::QuerySequence too_many;
  too_many.request.recent_frames = 5000;
  expectFailure(too_many, "recent_frames 5000 is more than the 400 frames");

  mrs_vpr::QuerySequence too_few_older;
  too_few_older.request.recent_frames = 200;  // 400 - 200 - 50 excluded leaves 150 < 200
  expectFailure(too_few_older, "leaves 150 searchable frames");

  auto zero_size = explicitQuery(100, 20, "mrs");
  zero_size.request.images[3] = sensor_msgs::Image();
  zero_size.request.images[3].encoding = "bgr8";
  expectFailure(zero_size, "images[3]");
  expectFailure(zero_size, "empty image (0 x 0");

  auto float_image = explicitQuery(100, 20, "mrs");
  float_image.request.images[5] = imageMessage(cv::Mat(64, 128, CV_32FC3, cv::Scalar(0.5, 0.5, 0.5)), 1.0, "32FC3");
  expectFailure(float_image, "images[5]");
  expectFailure(float_image, "unsupported encoding '32FC3'");

  auto semi_planar = explicitQuery(100, 20, "seqslam");
  semi_planar.request.images[0] = imageMessage(cv::Mat(96, 128, CV_8UC1, cv::Scalar(9)), 1.0, "nv21");
  expectFailure(semi_planar, "unsupported encoding 'nv21'");

  auto one_image = explicitQuery(100, 1, "mrs");
  expectFailure(one_image, "at least 2 images");

  auto both = explicitQuery(100, 20, "mrs");
  both.request.recent_frames = 10;
  expectFailure(both, "not both");

  // Still serving, with the right answer.
  auto good = explicitQuery(150, 30, "mrs");
  const auto response = call(good);
  ASSERT_TRUE(response.success) << response.message;
  EXPECT_NEAR(response.reference_index, route_.query_to_reference[179], kTolerance);
}

TEST_F(NodeTest, RecentFramesAndContinuousMode) {
  // The second traversal passes through the same camera topic: its frames join the map, and the
  // newest ones are the test sequence.
  const int first = 200;
  const int count = 60;
  auto_loop_closures_.clear();
  playIntoNodes(route_.query, first, first + count, kQueryStart);
  const int newest = first + count - 1;
  const int truth = route_.query_to_reference[static_cast<std::size_t>(newest)];
  const ros::Time newest_stamp(kQueryStart + (count - 1) * kFramePeriod);

  for (const std::string method : {"mrs", "seqslam"}) {
    SCOPED_TRACE(method);
    loop_closures_.clear();
    mrs_vpr::QuerySequence srv;
    srv.request.recent_frames = 50;
    srv.request.method = method;
    const auto response = call(srv);
    ASSERT_TRUE(response.success) << response.message;
    EXPECT_NEAR(response.reference_index, truth, kTolerance);
    EXPECT_LT(response.reference_index, 400 + count - 50 - 50);  // only older, non-excluded frames
    mrs_vpr::LoopClosure closure;
    ASSERT_TRUE(loop_closures_.waitFor([](const mrs_vpr::LoopClosure&) { return true; }, closure, 5.0));
    EXPECT_EQ(closure.reference_index, response.reference_index);
    EXPECT_EQ(closure.query_length, 50U);
    EXPECT_NEAR((closure.header.stamp - newest_stamp).toSec(), 0.0, 1e-6);
    EXPECT_EQ(closure.header.frame_id, "camera");
  }

  // The continuous-mode node answers on its own once the newest frame is in its map.
  mrs_vpr::LoopClosure automatic;
  ASSERT_TRUE(auto_loop_closures_.waitFor(
      [&](const mrs_vpr::LoopClosure& m) { return std::abs((m.header.stamp - newest_stamp).toSec()) < 1e-6; },
      automatic, 10.0));
  EXPECT_EQ(automatic.query_length, 30U);
  EXPECT_EQ(automatic.method, "mrs");
  EXPECT_NEAR(automatic.reference_index, truth, kTolerance);
}

TEST_F(NodeTest, ResetEmptiesTheMap) {
  std_srvs::Trigger trigger;
  ASSERT_TRUE(mrs_vpr::testing_support::callService("mrs_vpr/reset", trigger));
  EXPECT_TRUE(trigger.response.success);
  EXPECT_EQ(trigger.response.message, "cleared " + std::to_string(map_frames_) + " frames (no ~database)");
  mrs_vpr::MapInfo info;
  ASSERT_TRUE(map_info_.waitFor(
      [&](const mrs_vpr::MapInfo& m) {
        info = m;
        return m.frames == 0;
      },
      20.0));
  EXPECT_EQ(info.frames_received, map_frames_);

  auto srv = explicitQuery(100, 20, "mrs");
  expectFailure(srv, "reference map is empty");
}

TEST_F(NodeTest, AMapTooSmallToJudgeAnswersButSaysWhyNothingIsAccepted) {
  // After the reset: 40 frames, so a 10-frame sequence has at most 22 ends outside its answer's
  // window, too few wrong places to tell a true one from chance.
  constexpr int kFrames = 40;
  ASSERT_TRUE(mrs_vpr::testing_support::waitForSubscribers(image_pub_, 2, 20.0));
  for (int i = 0; i < kFrames; ++i) {
    image_pub_.publish(imageMessage(route_.reference[static_cast<std::size_t>(i)], 30000.0 + i * kFramePeriod));
    ros::WallDuration(0.002).sleep();
  }
  ASSERT_TRUE(map_info_.waitFor([&](const mrs_vpr::MapInfo& m) { return m.frames == kFrames; }, 20.0));
  for (const std::string method : {"mrs", "seqslam"}) {
    SCOPED_TRACE(method);
    mrs_vpr::QuerySequence srv;
    for (int i = 20; i < 30; ++i) {  // Frames of the map itself: the answer is right.
      srv.request.images.push_back(imageMessage(route_.reference[static_cast<std::size_t>(i)], 31000.0 + i));
    }
    srv.request.method = method;
    const auto response = call(srv);
    ASSERT_TRUE(response.success) << response.message;
    EXPECT_NEAR(response.reference_index, 29, 1);
    EXPECT_FALSE(response.accepted);
    EXPECT_FLOAT_EQ(response.confidence, 0.0F);
    EXPECT_NE(response.message.find("ends outside the answer's window"), std::string::npos) << response.message;
  }
}

/// Runs a command, returns its exit status and fills `output` with stdout and stderr.
int run(const std::string& command, std::string& output) {
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) {
    return -1;
  }
  std::array<char, 512> buffer{};
  while (std::fgets(buffer.data(), static_cast<int>(buffer.size()), pipe) != nullptr) {
    output += buffer.data();
  }
  const int status = pclose(pipe);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(NodeStartup, InvalidParametersAreFatalAndNamed) {
  std::string output;
  EXPECT_NE(run("rosrun mrs_vpr mrs_vpr_node __name:=mrs_vpr_bad_width _descriptor/image_width:=2", output), 0);
  EXPECT_NE(output.find("descriptor/image_width"), std::string::npos) << output;

  output.clear();
  EXPECT_NE(run("rosrun mrs_vpr mrs_vpr_node __name:=mrs_vpr_bad_tau _mrs/tau:=fast", output), 0);
  EXPECT_NE(output.find("~mrs/tau must be a number, got a string"), std::string::npos) << output;

  output.clear();
  EXPECT_NE(run("rosrun mrs_vpr mrs_vpr_node __name:=mrs_vpr_bad_stride _frame_stride:=0", output), 0);
  EXPECT_NE(output.find("~frame_stride must be in 1..10000, got 0"), std::string::npos) << output;

  // Beyond 32 bits, a whole number reaches the node as a double: out of range, not "a number".
  output.clear();
  EXPECT_NE(run("rosrun mrs_vpr mrs_vpr_node __name:=mrs_vpr_bad_capacity _max_frames:=99999999999", output), 0);
  EXPECT_NE(output.find("~max_frames must be "), std::string::npos) << output;
  EXPECT_NE(output.find(", got 99999999999"), std::string::npos) << output;

  // image_transport reads its own parameter and would take a number for "raw": the node checks its type.
  output.clear();
  EXPECT_NE(run("rosrun mrs_vpr mrs_vpr_node __name:=mrs_vpr_bad_transport _image_transport:=5", output), 0);
  EXPECT_NE(output.find("~image_transport must be a string, got an integer"), std::string::npos) << output;
}

}  // namespace

int main(int argc, char** argv) {
  return mrs_vpr::testing_support::runRostests(argc, argv, "mrs_vpr_node_rostest");
}
