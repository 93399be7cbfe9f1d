#pragma once

// A robot that drives, stands still and drives on, as the tests of keyframes by travel replay it:
// live on /tf (the node) and in a bag (the bag tools).

#include <string>
#include <vector>

#include <geometry_msgs/TransformStamped.h>
#include <ros/time.h>

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

/// `child` at x metres along `parent`'s x axis, unrotated, at `stamp`.
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

}  // namespace testing_support
}  // namespace mrs_vpr
