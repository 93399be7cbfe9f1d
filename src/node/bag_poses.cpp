#include "mrs_vpr/node/bag_poses.hpp"

#include <tf2/buffer_core.h>

#include "bag_reader_table.hpp"
#include "mrs_vpr/node/robot_position.hpp"

namespace mrs_vpr {
namespace bag {
namespace {

// tf2 forgets transforms older than its cache time before the newest one. A year keeps every
// transform of any bag, and stamp + cache time stays within ros::Time's range.
const ros::Duration kKeepEverything(365.0 * 24.0 * 3600.0);

}  // namespace

void forEachTransform(const std::string& bag_path, const TransformVisitor& visit) {
  bagReader().for_each_transform(bag_path, visit);
}

BagPoses::BagPoses(const std::string& bag_path, const BetweenMessages& between)
    : buffer_(std::make_unique<tf2::BufferCore>(kKeepEverything)) {
  if (between) between();
  forEachTransform(bag_path, [&](const geometry_msgs::TransformStamped& transform, bool is_static) {
    if (between) between();
    // tf2 reports a transform it refuses (NaN, an empty or equal frame pair) on the console and
    // goes on, as the node's listener does.
    buffer_->setTransform(transform, "bag", is_static);
  });
}

BagPoses::~BagPoses() = default;

std::optional<Eigen::Vector3d> BagPoses::positionAt(const std::string& odom_frame, const std::string& base_frame,
                                                    const ros::Time& stamp, std::string& why) const {
  return node::robotPositionFrom([&] { return buffer_->lookupTransform(odom_frame, base_frame, stamp); }, why);
}

}  // namespace bag
}  // namespace mrs_vpr
