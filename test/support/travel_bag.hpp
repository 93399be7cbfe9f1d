#pragma once

// A bag of a robot that drives, stands still and drives on: one camera frame at each pose, the
// poses on /tf (odom -> base_link) and the camera's mounting on /tf_static (base_link -> camera).

#include <string>
#include <vector>

#include <geometry_msgs/TransformStamped.h>
#include <rosbag/bag.h>
#include <sensor_msgs/Image.h>
#include <tf2_msgs/TFMessage.h>

namespace mrs_vpr {
namespace testing_support {

/// The robot's x along the drive: 4 m at 0.25 m a frame (17 frames, 0 to 4 m), 30 frames standing
/// at 4 m with 1 cm of odometry jitter, then 2 m at 0.5 m a frame (4 frames, 4.5 to 6 m): 51 frames,
/// of which a keyframe every metre keeps the 7 at 0, 1, ..., 6 m.
inline std::vector<double> driveStopDrive() {
  std::vector<double> x;
  for (int i = 0; i <= 16; ++i) x.push_back(0.25 * i);
  for (int i = 0; i < 30; ++i) x.push_back(4.0 + (i % 2 == 0 ? 0.01 : -0.01));
  for (int i = 1; i <= 4; ++i) x.push_back(4.0 + 0.5 * i);
  return x;
}

/// The stamp of frame `i`: 10 frames a second from t = 100 s.
inline ros::Time frameStamp(int i) { return ros::Time(100.0 + 0.1 * i); }

inline geometry_msgs::TransformStamped transformAt(const ros::Time& stamp, const std::string& parent,
                                                   const std::string& child, double x) {
  geometry_msgs::TransformStamped transform;
  transform.header.stamp = stamp;
  transform.header.frame_id = parent;
  transform.child_frame_id = child;
  transform.transform.translation.x = x;
  transform.transform.rotation.w = 1.0;
  return transform;
}

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
