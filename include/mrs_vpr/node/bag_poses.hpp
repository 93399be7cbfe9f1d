#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include <Eigen/Core>
#include <geometry_msgs/TransformStamped.h>
#include <ros/time.h>

#include "mrs_vpr/node/between_messages.hpp"

namespace tf2 {
class BufferCore;
}

namespace mrs_vpr {
namespace bag {

/// Called with each transform of a bag's /tf (is_static false) and /tf_static (true) messages.
using TransformVisitor = std::function<void(const geometry_msgs::TransformStamped& transform, bool is_static)>;

/// Hands every transform of the bag's /tf and /tf_static topics (tf2_msgs/TFMessage) to `visit`, in
/// bag order. Throws std::runtime_error naming the bag when it cannot be opened or has neither topic.
void forEachTransform(const std::string& bag_path, const TransformVisitor& visit);

/**
 * Where the robot was while a bag was recorded: every transform of its /tf and /tf_static in one
 * tf2 buffer that keeps them all, so that a pose can be looked up at any stamp of the bag, as the
 * node looks it up live.
 */
class BagPoses {
 public:
  /// Reads the bag's transforms, calling `between` between them. Throws
  /// std::runtime_error as forEachTransform does.
  explicit BagPoses(const std::string& bag_path, const BetweenMessages& between = {});
  ~BagPoses();
  BagPoses(const BagPoses&) = delete;
  BagPoses& operator=(const BagPoses&) = delete;

  /// The position of `base_frame` in `odom_frame` at `stamp`, interpolated between transforms;
  /// std::nullopt when tf cannot give it, with tf's reason in `why`.
  std::optional<Eigen::Vector3d> positionAt(const std::string& odom_frame, const std::string& base_frame,
                                            const ros::Time& stamp, std::string& why) const;

 private:
  std::unique_ptr<tf2::BufferCore> buffer_;
};

}  // namespace bag
}  // namespace mrs_vpr
