#pragma once

#include <string>

#include <ros/ros.h>

namespace mrs_vpr {
namespace testing_support {

/// A client of the service `name` over a persistent connection.
///
/// roscpp's one-shot calls sometimes fail on a loaded machine: the server closes its end right after
/// writing the response, and the client can see the hang-up before it has read the response
/// (ros/ros_comm#1976). On a persistent connection only the client closes, so a call fails only when
/// the server really is gone. Tests must not fail on that race, nor retry calls that change a map.
template <typename Service>
ros::ServiceClient persistentClient(ros::NodeHandle& nh, const std::string& name) {
  return nh.serviceClient<Service>(name, /*persistent=*/true);
}

/// One call of the service `name` over a connection of its own (see persistentClient).
template <typename Service>
bool callService(const std::string& name, Service& service) {
  ros::NodeHandle nh;
  ros::ServiceClient client = persistentClient<Service>(nh, name);
  return client.call(service);
}

}  // namespace testing_support
}  // namespace mrs_vpr
