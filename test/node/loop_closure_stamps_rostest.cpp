// LIO-SAM's external loop closures from two running nodes (see loop_closure_stamps.test): exactly the
// accepted answers of ~loop_closure arrive on the stamps topic, as [localised test frame, reference frame].
// The nodes run at the default sequence/alignment (centred): the localised frame is the middle of the
// test sequence, and ~loop_closure's header carries its stamp.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <ros/ros.h>
#include <std_msgs/Float64MultiArray.h>

#include "mrs_vpr/LoopClosure.h"
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

using mrs_vpr::LoopClosure;
using mrs_vpr::testing_support::imageMessage;
using mrs_vpr::testing_support::TopicInbox;
using Stamps = std_msgs::Float64MultiArray;

constexpr double kReferenceStart = 1000.0;  // stamp of reference frame 0 [s]
constexpr double kFramePeriod = 0.1;        // [s]

/// One node's ~query, ~map_info, ~loop_closure and stamps topic (lio_loop/loop_closure_detection in
/// its namespace, by the launch file's remapping).
struct NodeTopics {
  NodeTopics(ros::NodeHandle& nh, const std::string& ns)
      : stamps_topic(ns + "/lio_loop/loop_closure_detection"),
        query(mrs_vpr::testing_support::persistentClient<mrs_vpr::QuerySequence>(nh, ns + "/mrs_vpr/query")),
        map_info(nh, ns + "/mrs_vpr"),
        closures(nh, ns + "/mrs_vpr/loop_closure"),
        stamps(nh, stamps_topic) {}

  std::string stamps_topic;
  ros::ServiceClient query;
  mrs_vpr::testing_support::MapInfoWatch map_info;
  TopicInbox<LoopClosure> closures;
  TopicInbox<Stamps> stamps;
};

/// What the stamps topic must carry for these ~loop_closure messages: one [localised test frame,
/// reference frame] pair per accepted match whose two stamps are known and that is not restated for a
/// stopped frame, in the same order.
std::vector<std::vector<double>> expectedStamps(const std::vector<LoopClosure>& closures) {
  std::vector<std::vector<double>> expected;
  for (const LoopClosure& closure : closures) {
    if (closure.accepted && closure.reference_index >= 0 && !closure.header.stamp.isZero() &&
        !closure.reference_stamp.isZero() && closure.localised_keyframe_stamp == closure.header.stamp) {
      expected.push_back({closure.header.stamp.toSec(), closure.reference_stamp.toSec()});
    }
  }
  return expected;
}

class LoopClosureStampsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(ros::service::waitForService("queried/mrs_vpr/query", ros::Duration(30.0)));
    ASSERT_TRUE(ros::service::waitForService("continuous/mrs_vpr/query", ros::Duration(30.0)));
    image_pub_ = nh_.advertise<sensor_msgs::Image>("camera/image", 1000);
    for (NodeTopics* node : {&queried_, &continuous_}) {
      ASSERT_TRUE(node->closures.waitConnected());
      // A publisher on the remapped name: the launch file's argument took effect.
      ASSERT_TRUE(node->stamps.waitConnected()) << "nothing publishes " << node->stamps_topic;
    }
    if (map_frames_ == 0) {
      playIntoNodes(route_.reference, 0, static_cast<int>(route_.reference.size()), kReferenceStart);
    }
  }

  /// Publishes frames [begin, end) of `frames` stamped start + i * period and waits until both nodes
  /// have added them to their maps.
  void playIntoNodes(const std::vector<cv::Mat>& frames, int begin, int end, double start) {
    ASSERT_TRUE(mrs_vpr::testing_support::waitForSubscribers(image_pub_, 2, 20.0));
    for (int i = begin; i < end; ++i) {
      image_pub_.publish(imageMessage(frames[static_cast<std::size_t>(i)], start + (i - begin) * kFramePeriod));
      ros::WallDuration(0.002).sleep();
    }
    map_frames_ += static_cast<std::uint32_t>(end - begin);
    const std::uint32_t expected = map_frames_;
    for (NodeTopics* node : {&queried_, &continuous_}) {
      ASSERT_TRUE(node->map_info.waitFor([&](const mrs_vpr::MapInfo& m) { return m.frames == expected; }, 20.0))
          << "the map did not reach " << expected << " frames";
    }
  }

  /// An explicit test sequence: `frames` [first, first + count), stamped from `start`.
  static mrs_vpr::QuerySequence explicitQuery(const std::vector<cv::Mat>& frames, int first, int count,
                                              double start, const std::string& method = "") {
    mrs_vpr::QuerySequence srv;
    for (int i = 0; i < count; ++i) {
      srv.request.images.push_back(imageMessage(frames[static_cast<std::size_t>(first + i)], start + i * kFramePeriod));
    }
    srv.request.method = method;
    return srv;
  }

  /// Calls the node's ~query and returns the ~loop_closure of this answer (the one whose localised
  /// test frame is at `localised`).
  static LoopClosure ask(NodeTopics& node, mrs_vpr::QuerySequence& srv, const ros::Time& localised) {
    EXPECT_TRUE(node.query.call(srv)) << "the service call itself failed";
    EXPECT_TRUE(srv.response.success) << srv.response.message;
    LoopClosure closure;
    EXPECT_TRUE(
        node.closures.waitFor([&](const LoopClosure& m) { return at(m.header.stamp, localised); }, closure, 10.0))
        << "no ~loop_closure for the query whose localised frame is at " << localised;
    return closure;
  }

  /// Whether a stamp the node passed on is `expected`. A map frame's stamp goes through seconds as a
  /// double inside the map, which may move it by a nanosecond.
  static bool at(const ros::Time& stamp, const ros::Time& expected) {
    return std::abs((stamp - expected).toSec()) < 1e-6;
  }

  /// The stamps message whose localised test frame is at `localised`; whether one came within 10 s.
  static bool waitForStamps(NodeTopics& node, const ros::Time& localised, Stamps& found) {
    return node.stamps.waitFor(
        [&](const Stamps& m) { return m.data.size() == 2 && std::abs(m.data[0] - localised.toSec()) < 1e-6; }, found,
        10.0);
  }

  /// Ends a check with an accepted query of mapped frames, whose stamps are the last to come: once
  /// they are in, so is every message published before them, and the stamps topic must then hold
  /// exactly the expected pairs, equal to the last bit.
  void expectStampsOfAcceptedClosuresOnly(NodeTopics& node) {
    auto sentinel = explicitQuery(route_.query, 100, 40, 60000.0 + sentinels_++ * 100.0);
    const LoopClosure last = ask(node, sentinel, sentinel.request.images.at(20).header.stamp);  // the middle
    ASSERT_TRUE(last.accepted) << sentinel.response.message;
    Stamps last_stamps;
    ASSERT_TRUE(waitForStamps(node, last.header.stamp, last_stamps));
    const std::vector<LoopClosure> closures = node.closures.received();
    const std::vector<Stamps> received = node.stamps.received();
    const std::vector<std::vector<double>> expected = expectedStamps(closures);
    ASSERT_EQ(received.size(), expected.size()) << "of " << closures.size() << " answers on ~loop_closure";
    for (std::size_t i = 0; i < expected.size(); ++i) {
      SCOPED_TRACE("accepted closure " + std::to_string(i));
      EXPECT_TRUE(received[i].layout.dim.empty());
      ASSERT_EQ(received[i].data.size(), 2U);
      EXPECT_EQ(received[i].data[0], expected[i][0]);  // the localised test frame first, as LIO-SAM reads it
      EXPECT_EQ(received[i].data[1], expected[i][1]);
    }
  }

  const mrs_vpr::SyntheticRoute& route_ = mrs_vpr::testing_support::defaultRouteImages();
  const mrs_vpr::SyntheticRoute& unmapped_ = mrs_vpr::testing_support::unmappedRouteImages();
  static std::uint32_t map_frames_;
  static int sentinels_;

  ros::NodeHandle nh_;
  ros::Publisher image_pub_;
  NodeTopics queried_{nh_, "queried"};
  NodeTopics continuous_{nh_, "continuous"};
};

std::uint32_t LoopClosureStampsTest::map_frames_ = 0;
int LoopClosureStampsTest::sentinels_ = 0;

// The tests run in this order (gtest keeps declaration order) and share the nodes' maps.

TEST_F(LoopClosureStampsTest, ServiceQueriesWithImages) {
  int accepted = 0;
  int rejected = 0;
  double start = 10000.0;  // each query's stamps of its own
  // Mapped stretches (accepted) and an unmapped route (not accepted), with both methods.
  for (const std::string method : {"mrs", "seqslam"}) {
    for (const bool mapped : {true, false}) {
      SCOPED_TRACE(method + (mapped ? ", mapped" : ", unmapped"));
      auto srv = explicitQuery(mapped ? route_.query : unmapped_.query, 100, 40, start, method);
      start += 100.0;
      // The middle of the 40 images (every one a keyframe here) is the one localised.
      const ros::Time localised = srv.request.images.at(20).header.stamp;
      const LoopClosure closure = ask(queried_, srv, localised);
      EXPECT_EQ(closure.accepted, mapped) << srv.response.message;
      if (!closure.accepted) {
        ++rejected;
        continue;
      }
      ++accepted;
      Stamps stamps;
      ASSERT_TRUE(waitForStamps(queried_, localised, stamps));
      // [stamp of the image localised, stamp of the reference frame answered].
      EXPECT_EQ(stamps.data.at(0), localised.toSec());
      EXPECT_EQ(stamps.data.at(1), closure.reference_stamp.toSec());
      EXPECT_NEAR(stamps.data.at(1), kReferenceStart + closure.reference_index * kFramePeriod, 1e-3);
    }
  }
  EXPECT_EQ(accepted, 2);
  EXPECT_EQ(rejected, 2);
  expectStampsOfAcceptedClosuresOnly(queried_);
}

TEST_F(LoopClosureStampsTest, AnAcceptedAnswerToUnstampedImagesSaysWhyItsStampsAreNotPublished) {
  auto srv = explicitQuery(route_.query, 100, 40, 0.0);
  for (auto& image : srv.request.images) image.header.stamp = ros::Time();
  const LoopClosure closure = ask(queried_, srv, ros::Time());
  EXPECT_TRUE(closure.accepted);
  EXPECT_EQ(
      srv.response.message,
      "accepted; not published on /queried/lio_loop/loop_closure_detection: the localised test frame has no stamp");
  expectStampsOfAcceptedClosuresOnly(queried_);  // none for it
}

TEST_F(LoopClosureStampsTest, TheNewestMapFramesInQueriesAndInContinuousMode) {
  // The second traversal passes the camera: accepted answers, the localised map frame's stamp first.
  // Of the newest 50 frames (10..59 of those played) the middle one, 35, is localised.
  constexpr double kQueryStart = 5000.0;
  playIntoNodes(route_.query, 200, 260, kQueryStart);
  const ros::Time localised_query_frame(kQueryStart + 35 * kFramePeriod);

  mrs_vpr::QuerySequence recent;
  recent.request.recent_frames = 50;
  const LoopClosure answer = ask(queried_, recent, localised_query_frame);
  EXPECT_TRUE(answer.accepted) << recent.response.message;
  Stamps stamps;
  ASSERT_TRUE(waitForStamps(queried_, localised_query_frame, stamps));
  EXPECT_NEAR(stamps.data.at(1), kReferenceStart + answer.reference_index * kFramePeriod, 1e-3);

  // The continuous-mode node answers on its own once the newest frame is in its map, with the same 50
  // frames (auto_query_frames).
  const ros::Time continuous_frame = localised_query_frame;
  LoopClosure automatic;
  ASSERT_TRUE(continuous_.closures.waitFor([&](const LoopClosure& m) { return at(m.header.stamp, continuous_frame); },
                                           automatic, 10.0));
  EXPECT_TRUE(automatic.accepted);
  ASSERT_TRUE(waitForStamps(continuous_, continuous_frame, stamps));
  EXPECT_EQ(stamps.data.at(1), automatic.reference_stamp.toSec());

  // Then places not in the map: answers, but none accepted.
  constexpr double kUnmappedStart = 7000.0;
  playIntoNodes(unmapped_.query, 100, 160, kUnmappedStart);
  const ros::Time localised_unmapped_frame(kUnmappedStart + 35 * kFramePeriod);  // the middle of 10..59
  EXPECT_FALSE(ask(queried_, recent, localised_unmapped_frame).accepted) << recent.response.message;
  ASSERT_TRUE(continuous_.closures.waitFor(
      [&](const LoopClosure& m) { return at(m.header.stamp, localised_unmapped_frame); }, automatic, 10.0));
  EXPECT_FALSE(automatic.accepted);

  expectStampsOfAcceptedClosuresOnly(queried_);
  expectStampsOfAcceptedClosuresOnly(continuous_);
}

}  // namespace

int main(int argc, char** argv) {
  return mrs_vpr::testing_support::runRostests(argc, argv, "mrs_vpr_loop_closure_stamps_rostest");
}
