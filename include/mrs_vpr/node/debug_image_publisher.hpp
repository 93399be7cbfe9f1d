#pragma once

#include <atomic>
#include <cstdint>
#include <string>

#include <opencv2/core.hpp>
#include <ros/ros.h>
#include <std_msgs/Header.h>

#include "mrs_vpr/match_explanation.hpp"
#include "mrs_vpr/place_recognizer.hpp"

namespace mrs_vpr {
namespace node {

/**
 * `~debug_image` (sensor_msgs/Image, bgr8): the picture of each answered query
 * (visualization/match_image.hpp). It costs nothing while no one subscribes: the node asks wanted()
 * before a query and only then has the answer explained and drawn.
 */
class DebugImagePublisher {
 public:
  /// Advertises `debug_image` on `private_nh`.
  explicit DebugImagePublisher(ros::NodeHandle& private_nh);

  /// Whether someone subscribes, so that the next answer should be explained and drawn.
  bool wanted() const { return publisher_.getNumSubscribers() > 0; }

  /// Draws the answer, with `map_status` on its last line, and publishes it with `header` (the localised
  /// test frame's).
  void publish(const std_msgs::Header& header, const PlaceAnswer& answer, const MatchExplanation& explanation,
               const std::string& map_status);

  /// Images drawn since start-up (reported in ~map_info).
  std::uint64_t rendered() const { return rendered_.load(); }

 private:
  ros::Publisher publisher_;
  std::atomic<std::uint64_t> rendered_{0};
  cv::Mat image_;  // Drawn into again and again (only from the query thread).
};

}  // namespace node
}  // namespace mrs_vpr
