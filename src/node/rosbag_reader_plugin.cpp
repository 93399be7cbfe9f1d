// The only code linked with rosbag (which brings roslib, rospack and Python): loaded by bag_images.cpp
// on the first bag read, so that a tool run that reads no bag starts without them.
#include <fstream>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/CompressedImage.h>
#include <sensor_msgs/image_encodings.h>
#include <tf2_msgs/TFMessage.h>

#include "bag_reader_table.hpp"
#include "image_message_copy.hpp"
#include "mrs_vpr/image_codecs.hpp"
#include "mrs_vpr/node/compressed_format.hpp"

namespace mrs_vpr {
namespace bag {
namespace {

constexpr const char* kImageType = "sensor_msgs/Image";
constexpr const char* kCompressedType = "sensor_msgs/CompressedImage";
constexpr const char* kTransformTopic = "/tf";
constexpr const char* kStaticTransformTopic = "/tf_static";

/// Whether `path` begins as every bag of format 2.0 does.
bool beginsAsABag(const std::string& path) {
  static const std::string kMagic = "#ROSBAG V2.0\n";
  std::string start(kMagic.size(), '\0');
  std::ifstream file(path, std::ios::binary);
  return file.read(&start[0], static_cast<std::streamsize>(start.size())) && start == kMagic;
}

void openBag(rosbag::Bag& bag, const std::string& path) {
  try {
    bag.open(path, rosbag::bagmode::Read);
  } catch (const rosbag::BagException& error) {
    // A recording cut short (a full disk, a killed rosbag record) lacks the index at its end.
    const std::string hint =
        beginsAsABag(path) ? " (a bag whose recording was cut short can be mended with `rosbag reindex`)" : "";
    throw std::runtime_error("cannot open bag '" + path + "': " + error.what() + hint);
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
  throw std::runtime_error("bag '" + path + "' has no topic '" + topic +
                           "' (it has: " + (listing.empty() ? "nothing" : listing) + ")");
}

/// The name of a decoded Bayer camera's mosaic of `depth`: the format's encoding with its bits per value.
std::string mosaicEncoding(const std::string& format_encoding, int depth) {
  const std::string pattern = format_encoding.substr(0, format_encoding.find_first_of("0123456789"));
  return pattern + (depth == CV_16U ? "16" : "8");
}

/// Decodes as cv_bridge::toCvCopy does: the stream's own channels, named mono8/mono16, bgr8 or bgra8,
/// or, for a Bayer camera's mosaic, its Bayer encoding, as the node reads it. The caller names the
/// message in the error.
sensor_msgs::ImagePtr decode(const sensor_msgs::CompressedImageConstPtr& compressed) {
  const std::vector<std::uint8_t>& data = compressed->data;
  if (data.empty()) throw std::runtime_error("the compressed image holds no data (0 bytes)");
  // libjpeg would decode a truncated stream, grey where it is cut: such a frame is refused, as the node does.
  if (data.size() >= 2 && data[0] == 0xFF && data[1] == 0xD8 &&
      !image_codecs::jpegReachesEndOfImage(data.data(), data.size())) {
    throw std::runtime_error("the compressed image is a truncated JPEG stream (" + std::to_string(data.size()) +
                             " bytes, no end-of-image marker)");
  }
  cv::Mat image;
  try {
    image = image_codecs::decodeStrictly(data.data(), data.size());
  } catch (const image_codecs::CorruptJpeg& error) {
    throw std::runtime_error(std::string("the compressed image is corrupt JPEG data, which libjpeg cannot decode "
                                         "without making up pixels: ") +
                             error.what());
  } catch (const cv::Exception& error) {
    throw std::runtime_error("cannot decode the compressed image (format '" + compressed->format + "'): " +
                             error.err);
  }
  if (image.empty()) {
    throw std::runtime_error("cannot decode the compressed image (format '" + compressed->format + "', " +
                             std::to_string(data.size()) + " bytes): not an image OpenCV reads");
  }
  const std::string mosaic = node::compressedMosaicEncoding(compressed->format);
  if (!mosaic.empty() && (image.type() == CV_8UC1 || image.type() == CV_16UC1)) {
    return imageMessageOf(image, mosaicEncoding(mosaic, image.depth()), compressed->header);
  }
  switch (image.type()) {
    case CV_8UC1:
      return imageMessageOf(image, sensor_msgs::image_encodings::MONO8, compressed->header);
    case CV_16UC1:
      return imageMessageOf(image, sensor_msgs::image_encodings::MONO16, compressed->header);
    case CV_8UC3:
      return imageMessageOf(image, sensor_msgs::image_encodings::BGR8, compressed->header);
    case CV_8UC4:
      return imageMessageOf(image, sensor_msgs::image_encodings::BGRA8, compressed->header);
    default:
      throw std::runtime_error("the compressed image decodes to " + cv::typeToString(image.type()) +
                               ", which is not an image encoding read here");
  }
}

int countImagesWithRosbag(const std::string& bag_path, const std::string& topic) {
  rosbag::Bag bag;
  openBag(bag, bag_path);
  checkTopic(bag, bag_path, topic);
  return static_cast<int>(rosbag::View(bag, rosbag::TopicQuery(topic)).size());
}

void forEachImageWithRosbag(const std::string& bag_path, const std::string& topic, const ImageVisitor& visit, int start,
                            int count) {
  rosbag::Bag bag;
  openBag(bag, bag_path);
  checkTopic(bag, bag_path, topic);
  rosbag::View view(bag, rosbag::TopicQuery(topic));
  int index = 0;
  for (const rosbag::MessageInstance& instance : view) {
    if (count >= 0 && index >= start + count) break;
    if (index++ < start) continue;
    sensor_msgs::ImagePtr image;
    const auto where = [&] {
      return "message " + std::to_string(index - 1) + " of topic '" + topic + "' in bag '" + bag_path + "'";
    };
    try {
      if (instance.getDataType() == kImageType) {
        image = instance.instantiate<sensor_msgs::Image>();
      } else {
        image = decode(instance.instantiate<sensor_msgs::CompressedImage>());
      }
    } catch (const std::exception& error) {  // ros::serialization's "Buffer Overrun" names nothing
      throw std::runtime_error(where() + " cannot be read: " + error.what());
    }
    if (!image) throw std::runtime_error(where() + " cannot be read as " + instance.getDataType());
    if (image->header.stamp.isZero()) image->header.stamp = instance.getTime();
    visit(index - 1, image);
  }
}

void forEachTransformWithRosbag(const std::string& bag_path, const TransformVisitor& visit) {
  rosbag::Bag bag;
  openBag(bag, bag_path);
  rosbag::View view(bag, rosbag::TopicQuery(std::vector<std::string>{kTransformTopic, kStaticTransformTopic}));
  if (view.size() == 0) {
    throw std::runtime_error("bag '" + bag_path + "' has no /tf or /tf_static messages: the robot's poses are needed");
  }
  for (const rosbag::MessageInstance& instance : view) {
    tf2_msgs::TFMessage::ConstPtr message;
    try {
      message = instance.instantiate<tf2_msgs::TFMessage>();
    } catch (const std::exception& error) {  // ros::serialization's "Buffer Overrun" names nothing
      throw std::runtime_error("a message of topic '" + instance.getTopic() + "' in bag '" + bag_path +
                               "' cannot be read: " + error.what());
    }
    if (!message) {
      throw std::runtime_error("topic '" + instance.getTopic() + "' of bag '" + bag_path + "' carries " +
                               instance.getDataType() + ", not tf2_msgs/TFMessage");
    }
    const bool is_static = instance.getTopic() == kStaticTransformTopic;
    for (const geometry_msgs::TransformStamped& transform : message->transforms) visit(transform, is_static);
  }
}

}  // namespace
}  // namespace bag
}  // namespace mrs_vpr

extern "C" const mrs_vpr::bag::BagReaderTable* mrs_vpr_rosbag_reader_table() {
  static const mrs_vpr::bag::BagReaderTable table{&mrs_vpr::bag::countImagesWithRosbag,
                                                  &mrs_vpr::bag::forEachImageWithRosbag,
                                                  &mrs_vpr::bag::forEachTransformWithRosbag};
  return &table;
}
