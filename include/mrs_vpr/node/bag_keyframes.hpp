#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <ros/time.h>
#include <sensor_msgs/Image.h>

#include "mrs_vpr/node/bag_poses.hpp"
#include "mrs_vpr/node/travel_policy.hpp"

namespace mrs_vpr {
namespace bag {

/// Keyframes by travel, as the node's ~min_travel, ~odom_frame and ~base_frame choose them.
struct TravelSettings {
  double min_travel = 0.0;              ///< Metres between keyframes; 0 keeps every frame.
  std::string odom_frame = node::kDefaultOdomFrame;  ///< The frame the robot's positions are measured in.
  std::string base_frame = node::kDefaultBaseFrame;  ///< The robot's own frame.
};

/**
 * Chooses the keyframes of a bag's image stream by the distance the robot travelled, from the bag's
 * own /tf: the node's rule (TravelPolicy), so that a map or a test sequence taken from a bag is
 * spaced as the node would space it live. A frame whose pose tf cannot give is skipped and counted.
 */
class BagKeyframes {
 public:
  /// Reads the bag's poses when settings.min_travel > 0, calling `between` between the transforms.
  /// Throws std::invalid_argument for a negative or non-finite min_travel or an empty or equal frame
  /// pair, and std::runtime_error as BagPoses does (e.g. a bag without /tf).
  BagKeyframes(const std::string& bag_path, TravelSettings settings, const BetweenMessages& between = {});

  /// True when the frame stamped `stamp` is a keyframe; it is then the last keyframe.
  bool keep(const ros::Time& stamp);

  const TravelSettings& settings() const { return settings_; }
  /// Frames offered to keep() so far, kept or not.
  int frames() const { return kept_ + too_near_ + without_pose_; }
  int kept() const { return kept_; }
  /// Frames nearer than min_travel to the last keyframe.
  int tooNear() const { return too_near_; }
  /// Frames whose pose tf could not give; firstMissingPose() holds tf's reason for the first one.
  int withoutPose() const { return without_pose_; }
  const std::string& firstMissingPose() const { return first_missing_pose_; }
  /// One line for the user, e.g. "7 keyframes of 51 frames at min_travel 1 m (44 too near, 0 without a pose)".
  std::string summary() const;

 private:
  TravelSettings settings_;
  node::TravelPolicy policy_;
  std::unique_ptr<BagPoses> poses_;  ///< Only when min_travel > 0.
  int kept_ = 0;
  int too_near_ = 0;
  int without_pose_ = 0;
  std::string first_missing_pose_;
};

/// The first `count` messages of `topic` from message `start` on that `choose` takes, each offered
/// once, in order, calling `between` between the messages; the read ends with the last one chosen.
/// Throws std::runtime_error as forEachImage does, and when fewer follow `start` (naming what
/// `summary` says of the choice).
std::vector<sensor_msgs::ImageConstPtr> readChosen(const std::string& bag_path, const std::string& topic, int start,
                                                   int count,
                                                   const std::function<bool(const sensor_msgs::ImageConstPtr&)>& choose,
                                                   const std::function<std::string()>& summary,
                                                   const BetweenMessages& between = {});

/// The first `count` keyframes of `topic` from message `start` on, chosen by `keyframes` (readChosen),
/// calling `between` between the messages.
std::vector<sensor_msgs::ImageConstPtr> readKeyframes(const std::string& bag_path, const std::string& topic, int start,
                                                      int count, BagKeyframes& keyframes,
                                                      const BetweenMessages& between = {});

}  // namespace bag
}  // namespace mrs_vpr
