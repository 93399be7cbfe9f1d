#include "mrs_vpr/node/bag_images.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include <opencv2/imgproc.hpp>
#include <sensor_msgs/image_encodings.h>

#include "mrs_vpr/node/ros_stamp.hpp"
#include "mrs_vpr/number_text.hpp"
#include "../plugin_loader/plugin_loader.hpp"
#include "bag_reader_table.hpp"
#include "image_message_copy.hpp"

namespace mrs_vpr {
namespace bag {

const BagReaderTable& bagReader() {
  // A function-local static is initialised once, also when several threads read bags at once.
  static const BagReaderTable& table =
      plugins::load<BagReaderTable>(kBagReaderPluginFile, kBagReaderSymbol, "bag reader");
  return table;
}

bool isBagPath(const std::string& path) {
  if (path.size() < 4) return false;
  std::string extension = path.substr(path.size() - 4);
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension == ".bag";
}

int countImages(const std::string& bag_path, const std::string& topic) {
  return bagReader().count_images(bag_path, topic);
}

void forEachImage(const std::string& bag_path, const std::string& topic, const ImageVisitor& visit, int start,
                  int count) {
  bagReader().for_each_image(bag_path, topic, visit, start, count);
}

std::vector<sensor_msgs::ImageConstPtr> readImages(const std::string& bag_path, const std::string& topic,
                                                   int start, int count, const BetweenMessages& between) {
  if (start < 0 || count < 0) {
    throw std::runtime_error("invalid message range: start " + std::to_string(start) + ", count " +
                             std::to_string(count));
  }
  std::vector<sensor_msgs::ImageConstPtr> images;
  if (between) between();
  forEachImage(
      bag_path, topic,
      [&](int, const sensor_msgs::ImageConstPtr& image) {
        images.push_back(image);
        if (between) between();
      },
      start, count);
  if (static_cast<int>(images.size()) < count) {
    const int available = countImages(bag_path, topic);
    const std::string asked = "frames " + std::to_string(start) + ".." + std::to_string(start + count - 1);
    throw std::runtime_error("topic '" + topic + "' of bag '" + bag_path + "' has " + std::to_string(available) +
                             " images (0.." + std::to_string(available - 1) + "): " + asked +
                             (start < available ? " run past its last image" : " lie beyond its last image"));
  }
  return images;
}

void requireFrameRate(double rate) {
  if (!(rate > 0.0) || !std::isfinite(rate)) throw std::invalid_argument("--rate must be > 0 Hz");
  if (rate > kFastestFrameRate) {
    throw std::invalid_argument("--rate must be at most 1e9 Hz, one frame a nanosecond (a stamp's resolution), got " +
                                numberText(rate));
  }
}

ros::Time frameStamp(double start_seconds, long long index, double rate) {
  if (!(rate > 0.0) || !std::isfinite(rate)) throw std::invalid_argument("a frame rate must be > 0 Hz");
  const Stamp start = Stamp::fromSeconds(start_seconds);
  const double offset = static_cast<double>(index) / rate;
  const double latest = static_cast<double>(Stamp::kMaxNanoseconds) * 1e-9;
  // Compared in seconds first: the offset in nanoseconds may not even fit in 64 bits.
  const bool fits = offset >= 0.0 && offset <= latest &&
                    std::llround(offset * 1e9) <= Stamp::kMaxNanoseconds - start.nanoseconds();
  if (!fits) {
    std::ostringstream text;
    text.precision(12);
    text << "frame " << index << " at " << rate << " Hz from " << start.toString() << " s would be stamped "
         << start_seconds + offset << " s, beyond the latest ROS time ("
         << Stamp::fromNanoseconds(Stamp::kMaxNanoseconds).toString() << " s)";
    throw std::invalid_argument(text.str());
  }
  return node::rosTimeOf(Stamp::fromNanoseconds(start.nanoseconds() + std::llround(offset * 1e9)));
}

sensor_msgs::ImagePtr toImageMessage(const cv::Mat& image, const std::string& encoding, const ros::Time& stamp,
                                     const std::string& frame_id, std::uint32_t seq) {
  if (image.empty()) throw std::invalid_argument("cannot make a message of an empty image");
  if (encoding != sensor_msgs::image_encodings::BGR8 && encoding != sensor_msgs::image_encodings::MONO8) {
    throw std::invalid_argument("unsupported output encoding '" + encoding + "' (expected bgr8 or mono8)");
  }
  cv::Mat eight_bit = image;
  if (image.depth() == CV_16U) {
    image.convertTo(eight_bit, CV_8U, 1.0 / 257.0);
  } else if (image.depth() != CV_8U) {
    throw std::invalid_argument("unsupported pixel depth (expected 8 or 16 bits per channel)");
  }
  cv::Mat converted;
  const int channels = eight_bit.channels();
  if (encoding == sensor_msgs::image_encodings::MONO8) {
    if (channels == 1) converted = eight_bit;
    else if (channels == 3) cv::cvtColor(eight_bit, converted, cv::COLOR_BGR2GRAY);
    else if (channels == 4) cv::cvtColor(eight_bit, converted, cv::COLOR_BGRA2GRAY);
  } else {
    if (channels == 1) cv::cvtColor(eight_bit, converted, cv::COLOR_GRAY2BGR);
    else if (channels == 3) converted = eight_bit;
    else if (channels == 4) cv::cvtColor(eight_bit, converted, cv::COLOR_BGRA2BGR);
  }
  if (converted.empty()) {
    throw std::invalid_argument("unsupported number of channels: " + std::to_string(channels));
  }
  std_msgs::Header header;
  header.seq = seq;
  header.stamp = stamp;
  header.frame_id = frame_id;
  return imageMessageOf(converted, encoding, header);
}

}  // namespace bag
}  // namespace mrs_vpr
