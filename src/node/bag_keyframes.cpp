#include "mrs_vpr/node/bag_keyframes.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "mrs_vpr/node/bag_images.hpp"

namespace mrs_vpr {
namespace bag {
namespace {

void validate(const TravelSettings& settings) {
  if (!(std::isfinite(settings.min_travel) && settings.min_travel >= 0.0)) {
    std::ostringstream message;
    message << "min_travel must be a finite number of metres >= 0, got " << settings.min_travel;
    throw std::invalid_argument(message.str());
  }
  if (settings.min_travel > 0.0) {
    node::TravelPolicy::requireMeasurable(settings.odom_frame, settings.base_frame, "the odom frame", "the base frame",
                                          "min_travel");
  }
}

}  // namespace

BagKeyframes::BagKeyframes(const std::string& bag_path, TravelSettings settings, const BetweenMessages& between)
    : settings_(std::move(settings)), policy_(settings_.min_travel) {
  validate(settings_);
  if (policy_.enabled()) poses_ = std::make_unique<BagPoses>(bag_path, between);
}

bool BagKeyframes::keep(const ros::Time& stamp) {
  if (!policy_.enabled()) {
    ++kept_;
    return true;
  }
  std::string why;
  const std::optional<Eigen::Vector3d> position =
      poses_->positionAt(settings_.odom_frame, settings_.base_frame, stamp, why);
  if (!position) {
    if (without_pose_++ == 0) first_missing_pose_ = why;
    return false;
  }
  if (!policy_.wants(*position)) {
    ++too_near_;
    return false;
  }
  policy_.keep(*position);
  ++kept_;
  return true;
}

std::string BagKeyframes::summary() const {
  std::ostringstream line;
  line << kept_ << " keyframes of " << frames() << " frames at min_travel "
       << settings_.min_travel << " m (" << too_near_ << " too near, " << without_pose_ << " without a pose of '"
       << settings_.base_frame << "' in '" << settings_.odom_frame << "')";
  return line.str();
}

std::vector<sensor_msgs::ImageConstPtr> readKeyframes(const std::string& bag_path, const std::string& topic, int start,
                                                      int count, BagKeyframes& keyframes,
                                                      const BetweenMessages& between) {
  return readChosen(
      bag_path, topic, start, count,
      [&](const sensor_msgs::ImageConstPtr& image) { return keyframes.keep(image->header.stamp); },
      [&] { return keyframes.summary(); }, between);
}

std::vector<sensor_msgs::ImageConstPtr> readChosen(const std::string& bag_path, const std::string& topic, int start,
                                                   int count,
                                                   const std::function<bool(const sensor_msgs::ImageConstPtr&)>& choose,
                                                   const std::function<std::string()>& summary,
                                                   const BetweenMessages& between) {
  if (start < 0 || count < 0) {
    throw std::runtime_error("invalid keyframe range: start " + std::to_string(start) + ", count " +
                             std::to_string(count));
  }
  const int available = countImages(bag_path, topic);
  if (start >= available) {
    throw std::runtime_error("topic '" + topic + "' of bag '" + bag_path + "' has " + std::to_string(available) +
                             " messages (0.." + std::to_string(available - 1) + "): none from message " +
                             std::to_string(start) + " on");
  }
  std::vector<sensor_msgs::ImageConstPtr> chosen;
  if (count == 0) return chosen;
  // The read ends once enough are chosen: forEachImage stops where its visitor throws.
  struct EnoughChosen {};
  try {
    if (between) between();
    forEachImage(
        bag_path, topic,
        [&](int, const sensor_msgs::ImageConstPtr& image) {
          if (choose(image)) chosen.push_back(image);
          if (static_cast<int>(chosen.size()) == count) throw EnoughChosen{};
          if (between) between();
        },
        start);
  } catch (const EnoughChosen&) {
  }
  if (static_cast<int>(chosen.size()) < count) {
    throw std::runtime_error("topic '" + topic + "' of bag '" + bag_path + "' has " + std::to_string(chosen.size()) +
                             " keyframes from message " + std::to_string(start) + " on, fewer than " +
                             std::to_string(count) + ": " + summary());
  }
  return chosen;
}

}  // namespace bag
}  // namespace mrs_vpr
