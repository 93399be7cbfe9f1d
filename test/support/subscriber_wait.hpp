#pragma once

#include <cstdint>

#include <ros/ros.h>

namespace mrs_vpr {
namespace testing_support {

/// Waits up to `timeout` seconds until `count` subscribers are connected to `publisher`; whether
/// they are. What a new publisher sends before a subscriber has connected never reaches it.
inline bool waitForSubscribers(const ros::Publisher& publisher, std::uint32_t count, double timeout) {
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
  while (publisher.getNumSubscribers() < count && ros::ok() && ros::WallTime::now() < deadline) {
    ros::WallDuration(0.02).sleep();
  }
  return publisher.getNumSubscribers() >= count;
}

}  // namespace testing_support
}  // namespace mrs_vpr
