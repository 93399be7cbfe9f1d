#include "mrs_vpr/node/bag_images.hpp"

#include <algorithm>
#include <cctype>
#include <cstddef>
#include <cstdint>
#include <set>
#include <stdexcept>

#include <boost/make_shared.hpp>
#include <opencv2/imgproc.hpp>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/CompressedImage.h>
#include <sensor_msgs/image_encodings.h>

#include "mrs_vpr/image_codecs.hpp"

namespace mrs_vpr {
namespace bag {

namespace {

constexpr const char* kImageType = "sensor_msgs/Image";
constexpr const char* kCompressedType = "sensor_msgs/CompressedImage";

void openBag(rosbag::Bag& bag, const std::string& path) {
  try {
    bag.open(path, rosbag::bagmode::Read);
  } catch (const rosbag::BagException& error) {
    throw std::runtime_error("cannot open bag '" + path + "': " + error.what());
  }
}

/// Checks that `topic` exists and carries images; the message lists what the bag holds instead.
void checkTopic(const rosbag::Bag& bag, const std::string& path, const std::string& topic) {
  rosbag::View everything(bag);
  std::set<std::string> topics;
  for (const rosbag::ConnectionInfo* connection : everything.getConnections()) {
    if (connection->topic != topic) {
      topics.insert(connection->topic + " (" + connection->datatype + ")");
      continue;
    }
    if (connection->datatype != kImageType && connection->datatype != kCompressedType) {
      throw std::runtime_error("topic '" + topic + "' of bag '" + path + "' carries " + connection->datatype +
                               ", not sensor_msgs/Image or sensor_msgs/CompressedImage");
    }
    return;
  }
  std::string listing;
  for (const std::string& entry : topics) listing += (listing.empty() ? "" : ", ") + entry;
  throw std::runtime_error("bag '" + path + "' has no topic '" + topic + "' (it has: " +
                           (listing.empty() ? "nothing" : listing) + ")");
}

/// An image message holding a copy of `image` (rows packed, native byte order), as cv_bridge's
/// CvImage::toImageMsg makes it; without cv_bridge, whose codecs would load ~120 libraries at start-up.
sensor_msgs::ImagePtr messageOf(const cv::Mat& image, const std::string& encoding, const std_msgs::Header& header) {
  auto message = boost::make_shared<sensor_msgs::Image>();
  message->header = header;
  message->height = static_cast<std::uint32_t>(image.rows);
  message->width = static_cast<std::uint32_t>(image.cols);
  message->encoding = encoding;
  message->is_bigendian = 0;
  message->step = static_cast<std::uint32_t>(image.cols * image.elemSize());
  message->data.resize(static_cast<std::size_t>(message->step) * image.rows);
  cv::Mat packed(image.rows, image.cols, image.type(), message->data.data(), message->step);
  image.copyTo(packed);
  return message;
}

/// Decodes as cv_bridge::toCvCopy does: the stream's own channels, named mono8/mono16, bgr8 or bgra8.
sensor_msgs::ImagePtr decode(const sensor_msgs::CompressedImageConstPtr& compressed, const std::string& path) {
  cv::Mat image;
  try {
    const cv::Mat buffer(1, static_cast<int>(compressed->data.size()), CV_8UC1,
                         const_cast<std::uint8_t*>(compressed->data.data()));
    image = image_codecs::decode(buffer, cv::IMREAD_UNCHANGED);
  } catch (const cv::Exception& error) {
    throw std::runtime_error("cannot decode a compressed image of bag '" + path + "': " + error.what());
  }
  if (image.empty()) throw std::runtime_error("cannot decode a compressed image of bag '" + path + "'");
  switch (image.type()) {
    case CV_8UC1:
      return messageOf(image, sensor_msgs::image_encodings::MONO8, compressed->header);
    case CV_16UC1:
      return messageOf(image, sensor_msgs::image_encodings::MONO16, compressed->header);
    case CV_8UC3:
      return messageOf(image, sensor_msgs::image_encodings::BGR8, compressed->header);
    case CV_8UC4:
      return messageOf(image, sensor_msgs::image_encodings::BGRA8, compressed->header);
    default:
      throw std::runtime_error("a compressed image of bag '" + path + "' decodes to " +
                               cv::typeToString(image.type()) + ", which is not an image encoding read here");
  }
}

}  // namespace

bool isBagPath(const std::string& path) {
  if (path.size() < 4) return false;
  std::string extension = path.substr(path.size() - 4);
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension == ".bag";
}

int countImages(const std::string& bag_path, const std::string& topic) {
  rosbag::Bag bag;
  openBag(bag, bag_path);
  checkTopic(bag, bag_path, topic);
  return static_cast<int>(rosbag::View(bag, rosbag::TopicQuery(topic)).size());
}

void forEachImage(const std::string& bag_path, const std::string& topic,
                  const std::function<void(int index, const sensor_msgs::ImageConstPtr& image)>& visit,
                  int start, int count) {
  rosbag::Bag bag;
  openBag(bag, bag_path);
  checkTopic(bag, bag_path, topic);
  rosbag::View view(bag, rosbag::TopicQuery(topic));
  int index = 0;
  for (const rosbag::MessageInstance& instance : view) {
    if (count >= 0 && index >= start + count) break;
    if (index++ < start) continue;
    sensor_msgs::ImagePtr image;
    if (instance.getDataType() == kImageType) {
      image = instance.instantiate<sensor_msgs::Image>();
    } else {
      image = decode(instance.instantiate<sensor_msgs::CompressedImage>(), bag_path);
    }
    if (!image) throw std::runtime_error("cannot read message " + std::to_string(index - 1) + " of '" + topic + "'");
    if (image->header.stamp.isZero()) image->header.stamp = instance.getTime();
    visit(index - 1, image);
  }
}

std::vector<sensor_msgs::ImageConstPtr> readImages(const std::string& bag_path, const std::string& topic,
                                                   int start, int count) {
  if (start < 0 || count < 0) {
    throw std::runtime_error("invalid message range: start " + std::to_string(start) + ", count " +
                             std::to_string(count));
  }
  std::vector<sensor_msgs::ImageConstPtr> images;
  forEachImage(
      bag_path, topic, [&images](int, const sensor_msgs::ImageConstPtr& image) { images.push_back(image); }, start,
      count);
  if (static_cast<int>(images.size()) < count) {
    const int available = countImages(bag_path, topic);
    throw std::runtime_error("topic '" + topic + "' of bag '" + bag_path + "' has " + std::to_string(available) +
                             " images; frames " + std::to_string(start) + ".." + std::to_string(start + count - 1) +
                             " do not exist");
  }
  return images;
}

sensor_msgs::ImagePtr toImageMessage(const cv::Mat& image, const std::string& encoding, const ros::Time& stamp,
                                     const std::string& frame_id) {
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
  header.stamp = stamp;
  header.frame_id = frame_id;
  return messageOf(converted, encoding, header);
}

}  // namespace bag
}  // namespace mrs_vpr
