#pragma once

#include <stdexcept>
#include <string>

#include <Eigen/Core>

namespace mrs_vpr {
namespace node {

/// The tf frames travel is measured in and of by default (~odom_frame, ~base_frame; the bag tools'
/// --odom-frame, --base-frame): REP 105's names.
inline constexpr const char* kDefaultOdomFrame = "odom";
inline constexpr const char* kDefaultBaseFrame = "base_link";

/**
 * Decides which frames become keyframes by the distance the robot has travelled: a frame is kept
 * when the robot is at least `min_travel` metres (straight line, in the odometry frame) from where
 * the last keyframe was taken. The search's trajectories assume that the robot covers about as much
 * ground per frame as when the map was taken; frames taken at fixed distances give that at any
 * speed, and a robot that stands still adds none (a stop within a test sequence would otherwise
 * place it ahead of where it is). min_travel = 0 keeps every frame. No ROS inside, and defined
 * here, so that the node and the bag tools use it without linking each other's libraries.
 */
class TravelPolicy {
 public:
  explicit TravelPolicy(double min_travel) : min_travel_(min_travel) {}

  /// Whether travel can be measured between these frames: two different tf frame names.
  static bool measurableBetween(const std::string& odom_frame, const std::string& base_frame) {
    return isFrameName(odom_frame) && isFrameName(base_frame) && odom_frame != base_frame;
  }
  /// Throws std::invalid_argument, in the same words wherever the frames are set, unless
  /// measurableBetween(); the names are those of the settings, e.g. "~odom_frame".
  static void requireMeasurable(const std::string& odom_frame, const std::string& base_frame,
                                const std::string& odom_name, const std::string& base_name,
                                const std::string& travel_name) {
    if (measurableBetween(odom_frame, base_frame)) return;
    throw std::invalid_argument(odom_name + " and " + base_name + " must name two different tf frames, without a "
                                "leading '/' (tf2 refuses it), when " + travel_name + " > 0 (got '" + odom_frame +
                                "' and '" + base_frame + "')");
  }
  /// A name tf2 looks up: not empty, and without tf1's leading '/', which tf2 refuses in every lookup.
  static bool isFrameName(const std::string& frame) { return !frame.empty() && frame.front() != '/'; }

  /// Whether frames are chosen by distance at all (min_travel > 0).
  bool enabled() const { return min_travel_ > 0.0; }
  /// True when a frame taken at `position` should be kept. Does not remember it: call keep() once
  /// the frame has really been added.
  bool wants(const Eigen::Vector3d& position) const {
    return !enabled() || !has_keyframe_ || (position - last_position_).norm() >= min_travel_;
  }
  /// Records where a keyframe was taken.
  void keep(const Eigen::Vector3d& position) {
    has_keyframe_ = true;
    last_position_ = position;
  }
  /// Forgets the last keyframe (after the map is reset or replaced).
  void reset() { has_keyframe_ = false; }

 private:
  double min_travel_;
  bool has_keyframe_ = false;
  Eigen::Vector3d last_position_ = Eigen::Vector3d::Zero();
};

}  // namespace node
}  // namespace mrs_vpr
