#pragma once

// A bag of a robot that drives, stands still and drives on (travel_drive.hpp): one camera frame at
// each pose, the poses on /tf (odom -> base_link) and the camera's mounting on /tf_static
// (base_link -> camera).

#include <string>
#include <vector>

#include <rosbag/bag.h>
#include <sensor_msgs/Image.h>
#include <tf2_msgs/TFMessage.h>

#include "support/travel_drive.hpp"

namespace mrs_vpr {
namespace testing_support {

/// The stamp of frame `i`: 10 frames a second from t = 100 s.
inline ros::Time frameStamp(int i) { return ros::Time(100.0 + 0.1 * i); }

/// Writes the drive to `path`: frame i on `topic` and the pose at x[i] on /tf, both at frameStamp(i),
/// the pose written first (as a robot's tf arrives before its camera's frame is handled). Without
/// `with_poses`, only the frames.
inline void writeTravelBag(const std::string& path, const std::string& topic, const std::vector<double>& x,
                           bool with_poses = true) {
  rosbag::Bag bag(path, rosbag::bagmode::Write);
  if (with_poses) {
    tf2_msgs::TFMessage mounting;
    mounting.transforms.push_back(transformAt(frameStamp(0), "base_link", "camera", 0.25));
    bag.write("/tf_static", frameStamp(0), mounting);
  }
  for (int i = 0; i < static_cast<int>(x.size()); ++i) {
    const ros::Time stamp = frameStamp(i);
    if (with_poses) {
      tf2_msgs::TFMessage pose;
      pose.transforms.push_back(transformAt(stamp, "odom", "base_link", x[static_cast<std::size_t>(i)]));
      bag.write("/tf", stamp, pose);
    }
    sensor_msgs::Image image;
    image.header.stamp = stamp;
    image.header.frame_id = "camera";
    image.encoding = "mono8";
    image.width = 16;
    image.height = 8;
    image.step = 16;
    image.data.assign(16 * 8, static_cast<std::uint8_t>(8 * i % 256));
    bag.write(topic, stamp, image);
  }
  bag.close();
}

}  // namespace testing_support
}  // namespace mrs_vpr
