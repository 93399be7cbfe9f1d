#include "mrs_vpr/node/debug_image_publisher.hpp"

#include <chrono>

#include <cv_bridge/cv_bridge.h>
#include <sensor_msgs/Image.h>

#include "mrs_vpr/visualization/match_image.hpp"

namespace mrs_vpr {
namespace node {

DebugImagePublisher::DebugImagePublisher(ros::NodeHandle& private_nh)
    : publisher_(private_nh.advertise<sensor_msgs::Image>("debug_image", 1)) {}

void DebugImagePublisher::publish(const std_msgs::Header& header, const PlaceAnswer& answer,
                                  const MatchExplanation& explanation, const std::string& map_status) {
  const auto start = std::chrono::steady_clock::now();
  visualization::renderMatchImage(explanation, answer, image_, map_status);
  ++rendered_;
  publisher_.publish(cv_bridge::CvImage(header, "bgr8", image_).toImageMsg());
  ROS_DEBUG("mrs_vpr: debug image drawn and published in %.2f ms",
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
}

}  // namespace node
}  // namespace mrs_vpr
