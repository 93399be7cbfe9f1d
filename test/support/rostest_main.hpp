#pragma once

#include <gtest/gtest.h>
#include <ros/ros.h>

namespace mrs_vpr {
namespace testing_support {

/// The main() of a rostest binary: GoogleTest's flags, then ROS as `node_name`, with one spinner
/// thread that delivers the tests' subscriptions while the tests wait.
inline int runRostests(int argc, char** argv, const char* node_name) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, node_name);
  ros::AsyncSpinner spinner(1);
  spinner.start();
  const int result = RUN_ALL_TESTS();
  spinner.stop();
  ros::shutdown();
  return result;
}

}  // namespace testing_support
}  // namespace mrs_vpr
