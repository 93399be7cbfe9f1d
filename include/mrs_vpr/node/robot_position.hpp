#pragma once

#include <optional>
#include <string>

#include <Eigen/Core>
#include <tf2/exceptions.h>

namespace mrs_vpr {
namespace node {

/// The translation of the transform that `lookup` returns (a tf lookup of the robot's frame in the
/// odometry frame): where the robot was. Nothing when tf cannot give it, with tf's reason in `why`.
/// The node (a live tf2_ros::Buffer) and the bag tools (a bag's tf2::BufferCore) both read it so.
template <typename Lookup>
std::optional<Eigen::Vector3d> robotPositionFrom(const Lookup& lookup, std::string& why) {
  try {
    const auto& t = lookup().transform.translation;
    return Eigen::Vector3d(t.x, t.y, t.z);
  } catch (const tf2::TransformException& exception) {
    why = exception.what();
    return std::nullopt;
  }
}

}  // namespace node
}  // namespace mrs_vpr
