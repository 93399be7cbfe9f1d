#pragma once

#include <string>

#include <cv_bridge/cv_bridge.h>
#include <opencv2/core.hpp>
#include <sensor_msgs/Image.h>

namespace mrs_vpr {
namespace testing_support {

/// A camera frame as the node receives it: `image` in `encoding`, stamped, from frame "camera".
inline sensor_msgs::Image imageMessage(const cv::Mat& image, double stamp, const std::string& encoding = "bgr8") {
  std_msgs::Header header;
  header.stamp = ros::Time(stamp);
  header.frame_id = "camera";
  return *cv_bridge::CvImage(header, encoding, image).toImageMsg();
}

}  // namespace testing_support
}  // namespace mrs_vpr
