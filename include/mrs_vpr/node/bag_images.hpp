#pragma once

#include <functional>
#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <ros/time.h>
#include <sensor_msgs/Image.h>

#include "mrs_vpr/node/between_messages.hpp"

namespace mrs_vpr {
namespace bag {

/// Called with each image message read from a bag and its index over the topic (from 0).
using ImageVisitor = std::function<void(int index, const sensor_msgs::ImageConstPtr& image)>;

/// Number of image messages (sensor_msgs/Image or sensor_msgs/CompressedImage) on `topic` of a bag.
/// Throws std::runtime_error when the bag cannot be opened or the topic holds no image messages.
int countImages(const std::string& bag_path, const std::string& topic);

/**
 * Hands the image messages of `topic` to `visit` in bag order (index counted from 0 over the topic),
 * starting at message `start` and stopping after `count` messages (count < 0: to the end).
 * sensor_msgs/CompressedImage messages are decoded to mono8, mono16, bgr8 or bgra8 first. A header stamp of zero is
 * replaced by the time the message was recorded.
 * Throws std::runtime_error naming the bag and topic when the bag cannot be opened, the topic holds
 * no image messages, or a compressed image cannot be decoded.
 *
 * Bags are read by a plugin (libmrs_vpr_rosbag_reader.so, beside this library) opened on the first
 * call, as rosbag brings roslib, rospack and Python: a program that reads no bag starts without them.
 * countImages and forEachImage throw std::runtime_error ("cannot load the bag reader: ...") when it
 * cannot be loaded.
 */
void forEachImage(const std::string& bag_path, const std::string& topic, const ImageVisitor& visit, int start = 0,
                  int count = -1);

/// Messages [start, start + count) of `topic`, calling `between` between them. Throws
/// std::runtime_error as forEachImage does, and when the topic holds fewer messages.
std::vector<sensor_msgs::ImageConstPtr> readImages(const std::string& bag_path, const std::string& topic,
                                                   int start, int count, const BetweenMessages& between = {});

/// True when `path` names a bag file (by its extension), so that a tool can accept folders and bags.
bool isBagPath(const std::string& path);

/// The fastest frame rate that frameStamp() stamps: one frame a nanosecond, a stamp's resolution;
/// faster frames would share stamps.
constexpr double kFastestFrameRate = 1e9;
/// Throws std::invalid_argument, in the words of a tool's `--rate`, unless 0 < `rate` <= kFastestFrameRate.
void requireFrameRate(double rate);

/**
 * The stamp of frame `index` of a recording at `rate` Hz from `start_seconds` (Unix time): start +
 * index / rate, to the nanosecond from the start (never accumulated, so it never drifts). Throws
 * std::invalid_argument naming the frame and its stamp when that is beyond the latest ROS time, and
 * when `start_seconds` is no ROS time or `rate` is not positive.
 */
ros::Time frameStamp(double start_seconds, long long index, double rate);

/// An image message of an 8-bit image in `encoding` ("bgr8" or "mono8"), converting colour, alpha
/// and 16-bit depth as needed, numbered `seq` (header.seq: the image's number in its recording, which
/// the node keeps as a map frame's `sequence` and mrs_vpr_eval reads as its frame number). Throws
/// std::invalid_argument for another encoding or an empty image.
sensor_msgs::ImagePtr toImageMessage(const cv::Mat& image, const std::string& encoding, const ros::Time& stamp,
                                     const std::string& frame_id, std::uint32_t seq);

}  // namespace bag
}  // namespace mrs_vpr
