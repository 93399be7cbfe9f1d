// Keyframes of a bag by the distance travelled, from the bag's own /tf (what build_map and
// query_bag --min-travel use).

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "mrs_vpr/node/bag_images.hpp"
#include "mrs_vpr/node/bag_keyframes.hpp"
#include "support/error_message.hpp"
#include "support/temporary_folder.hpp"
#include "support/travel_bag.hpp"

namespace mrs_vpr {
namespace bag {
namespace {

using testing_support::driveStopDrive;
using testing_support::frameStamp;

constexpr const char* kTopic = "/camera/image_raw";

class BagKeyframesTest : public ::testing::Test {
 protected:
  BagKeyframesTest() : folder_("mrs_vpr_bag_keyframes_test") {
    testing_support::writeTravelBag(bag(), kTopic, driveStopDrive());
  }
  std::string bag() const { return folder_.path("drive.bag"); }
  std::string bagWithoutPoses() const {
    const std::string path = folder_.path("no_poses.bag");
    testing_support::writeTravelBag(path, kTopic, driveStopDrive(), /*with_poses=*/false);
    return path;
  }
  /// Indices of the frames `keyframes` keeps, offering it every frame of the drive in order.
  static std::vector<int> keptFrames(BagKeyframes& keyframes) {
    std::vector<int> kept;
    for (int i = 0; i < static_cast<int>(driveStopDrive().size()); ++i) {
      if (keyframes.keep(frameStamp(i))) kept.push_back(i);
    }
    return kept;
  }

  testing_support::TemporaryFolder folder_;
};

TEST_F(BagKeyframesTest, KeepsAFrameEachMetreAndNoneWhileTheRobotStandsStill) {
  TravelSettings travel;
  travel.min_travel = 1.0;
  BagKeyframes keyframes(bag(), travel);
  // The frames at 0, 1, 2, 3 and 4 m (every fourth of the first drive), then 5 and 6 m (every second
  // frame after the stop): none of the 30 frames of the stop, whose odometry jitters by 1 cm.
  EXPECT_EQ(keptFrames(keyframes), (std::vector<int>{0, 4, 8, 12, 16, 48, 50}));
  EXPECT_EQ(keyframes.kept(), 7);
  EXPECT_EQ(keyframes.tooNear(), 44);
  EXPECT_EQ(keyframes.withoutPose(), 0);
  EXPECT_EQ(keyframes.summary(),
            "7 keyframes of 51 frames at min_travel 1 m (44 too near, 0 without a pose of 'base_link' in 'odom')");
}

TEST_F(BagKeyframesTest, ACameraFrameBehindAStaticTransformIsSpacedAlike) {
  // camera is 0.25 m ahead of base_link, known only from /tf_static.
  TravelSettings travel;
  travel.min_travel = 1.0;
  travel.base_frame = "camera";
  BagKeyframes keyframes(bag(), travel);
  EXPECT_EQ(keptFrames(keyframes), (std::vector<int>{0, 4, 8, 12, 16, 48, 50}));
  EXPECT_EQ(keyframes.withoutPose(), 0);
}

TEST_F(BagKeyframesTest, AFrameWithoutAPoseIsSkippedCountedAndExplained) {
  TravelSettings travel;
  travel.min_travel = 1.0;
  BagKeyframes keyframes(bag(), travel);
  // Before the first pose: tf cannot tell where the robot was.
  EXPECT_FALSE(keyframes.keep(ros::Time(50.0)));
  EXPECT_EQ(keyframes.withoutPose(), 1);
  EXPECT_NE(keyframes.firstMissingPose().find("extrapolation"), std::string::npos) << keyframes.firstMissingPose();
  // A frame the bag has no frame for at all.
  travel.base_frame = "gripper";
  BagKeyframes unknown(bag(), travel);
  EXPECT_FALSE(unknown.keep(frameStamp(3)));
  EXPECT_NE(unknown.firstMissingPose().find("gripper"), std::string::npos) << unknown.firstMissingPose();
  // The frames after it are still chosen.
  EXPECT_EQ(keptFrames(keyframes), (std::vector<int>{0, 4, 8, 12, 16, 48, 50}));
}

TEST_F(BagKeyframesTest, OffKeepsEveryFrameAndNeedsNoPoses) {
  BagKeyframes keyframes(bagWithoutPoses(), TravelSettings{});
  EXPECT_EQ(keptFrames(keyframes).size(), driveStopDrive().size());
  EXPECT_EQ(keyframes.tooNear(), 0);
}

TEST_F(BagKeyframesTest, ABagWithoutTfIsRefusedByName) {
  TravelSettings travel;
  travel.min_travel = 1.0;
  const std::string path = bagWithoutPoses();
  const std::string message = testing_support::runtimeErrorMessage([&] { BagKeyframes keyframes(path, travel); });
  EXPECT_NE(message.find("no /tf or /tf_static"), std::string::npos) << message;
  EXPECT_NE(message.find(path), std::string::npos) << message;
}

TEST_F(BagKeyframesTest, BadSettingsAreRefused) {
  for (double bad : {-1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    TravelSettings travel;
    travel.min_travel = bad;
    const std::string message = testing_support::invalidArgumentMessage([&] { BagKeyframes keyframes(bag(), travel); });
    EXPECT_NE(message.find("min_travel must be"), std::string::npos) << bad << ": " << message;
  }
  for (const std::string& base_frame : {"odom", "/base_link"}) {
    TravelSettings refused;
    refused.min_travel = 1.0;
    refused.base_frame = base_frame;
    const std::string message =
        testing_support::invalidArgumentMessage([&] { BagKeyframes keyframes(bag(), refused); });
    EXPECT_NE(message.find("the odom frame and the base frame must name two different tf frames, without a leading"),
              std::string::npos)
        << message;
  }
}

TEST_F(BagKeyframesTest, ReadKeyframesTakesCountKeyframesFromStart) {
  TravelSettings travel;
  travel.min_travel = 1.0;
  BagKeyframes keyframes(bag(), travel);
  // From frame 10 (2.5 m): 2.5, 3.5 and, after the stop at 4 m (0.5 m on), 4.5 m.
  const std::vector<sensor_msgs::ImageConstPtr> images = readKeyframes(bag(), kTopic, 10, 3, keyframes);
  ASSERT_EQ(images.size(), 3U);
  EXPECT_EQ(images[0]->header.stamp, frameStamp(10));
  EXPECT_EQ(images[1]->header.stamp, frameStamp(14));
  EXPECT_EQ(images[2]->header.stamp, frameStamp(47));

  BagKeyframes too_few(bag(), travel);
  const std::string message =
      testing_support::runtimeErrorMessage([&] { readKeyframes(bag(), kTopic, 10, 5, too_few); });
  EXPECT_NE(message.find("has 4 keyframes from message 10 on, fewer than 5"), std::string::npos) << message;
}

TEST_F(BagKeyframesTest, ReadChosenOffersEachMessageOnceInOrderAndNamesTheChoiceWhenTooFewFollow) {
  std::vector<ros::Time> offered;
  const auto every_fifth = [&](const sensor_msgs::ImageConstPtr& image) {
    offered.push_back(image->header.stamp);
    return offered.size() % 5 == 1;
  };
  const std::vector<sensor_msgs::ImageConstPtr> images =
      readChosen(bag(), kTopic, 3, 4, every_fifth, [] { return std::string("every fifth"); });
  ASSERT_EQ(images.size(), 4U);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(images[static_cast<std::size_t>(i)]->header.stamp, frameStamp(3 + 5 * i));
  ASSERT_EQ(offered.size(), 16U);  // The read ends with the last one chosen.
  for (std::size_t i = 0; i < 16; ++i) EXPECT_EQ(offered[i], frameStamp(3 + static_cast<int>(i)));
  offered.clear();
  const std::string message = testing_support::runtimeErrorMessage(
      [&] { readChosen(bag(), kTopic, 3, 100, every_fifth, [] { return std::string("every fifth"); }); });
  EXPECT_NE(message.find("fewer than 100: every fifth"), std::string::npos) << message;
  // A start beyond the last message is said so: not "has 0 keyframes from message N on".
  const int messages = static_cast<int>(driveStopDrive().size());
  const std::string beyond = testing_support::runtimeErrorMessage(
      [&] { readChosen(bag(), kTopic, messages + 10, 2, every_fifth, [] { return std::string("every fifth"); }); });
  EXPECT_NE(beyond.find("has " + std::to_string(messages) + " messages (0.." + std::to_string(messages - 1) +
                        "): none from message " + std::to_string(messages + 10) + " on"),
            std::string::npos)
      << beyond;
  // Too few images from a start that exists: they run past the last, which is named.
  const std::string past = testing_support::runtimeErrorMessage([&] { readImages(bag(), kTopic, messages - 1, 2); });
  EXPECT_NE(past.find("has " + std::to_string(messages) + " images (0.." + std::to_string(messages - 1) +
                      "): frames " + std::to_string(messages - 1) + ".." + std::to_string(messages) +
                      " run past its last image"),
            std::string::npos)
      << past;
}

TEST_F(BagKeyframesTest, EveryReaderStopsWhenItsCallBetweenMessagesThrows) {
  // A tool's Ctrl-C: the call throws once it has come, and the read stops there with that error.
  struct Stop {};
  int calls = 0;
  const auto stopAfter = [&calls](int allowed) {
    return [&calls, allowed] {
      if (++calls > allowed) throw Stop{};
    };
  };
  const int messages = static_cast<int>(driveStopDrive().size());
  EXPECT_THROW(readImages(bag(), kTopic, 0, messages, stopAfter(5)), Stop);
  EXPECT_EQ(calls, 6);  // Before the first message and after each of the first five.
  calls = 0;
  EXPECT_EQ(readImages(bag(), kTopic, 0, messages, stopAfter(messages + 1)).size(),
            static_cast<std::size_t>(messages));
  EXPECT_EQ(calls, messages + 1);

  TravelSettings travel;
  travel.min_travel = 1.0;
  calls = 0;
  EXPECT_THROW(BagKeyframes(bag(), travel, stopAfter(3)), Stop);  // While it reads the bag's /tf.
  EXPECT_EQ(calls, 4);
  calls = 0;
  BagKeyframes keyframes(bag(), travel, [&calls] { ++calls; });
  EXPECT_GT(calls, messages);  // Once a transform of the bag's /tf, which has one a frame and more.
  calls = 0;
  EXPECT_THROW(readKeyframes(bag(), kTopic, 0, 7, keyframes, stopAfter(10)), Stop);
  EXPECT_EQ(calls, 11);
  calls = 0;  // Also between messages that are not chosen.
  const auto none = [](const sensor_msgs::ImageConstPtr&) { return false; };
  EXPECT_THROW(readChosen(bag(), kTopic, 0, 2, none, [] { return std::string(); }, stopAfter(5)), Stop);
  EXPECT_EQ(calls, 6);
}

}  // namespace
}  // namespace bag
}  // namespace mrs_vpr
