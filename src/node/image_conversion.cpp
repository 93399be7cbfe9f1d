#include "mrs_vpr/node/image_conversion.hpp"

#include <array>
#include <cstddef>
#include <stdexcept>


namespace mrs_vpr {
namespace node {
namespace {

struct EncodingInfo {
  const char* name;
  int bytes_per_pixel;
  ChannelOrder order;
};

const std::array<EncodingInfo, 6> kEncodings{{
    {"mono8", 1, ChannelOrder::kBgr},
    {"mono16", 2, ChannelOrder::kBgr},
    {"bgr8", 3, ChannelOrder::kBgr},
    {"rgb8", 3, ChannelOrder::kRgb},
    {"bgra8", 4, ChannelOrder::kBgr},
    {"rgba8", 4, ChannelOrder::kRgb},
}};

const EncodingInfo* findEncoding(const std::string& encoding) {
  for (const auto& info : kEncodings) {
    if (encoding == info.name) {
      return &info;
    }
  }
  return nullptr;
}

}  // namespace

bool isSupportedEncoding(const std::string& encoding) { return findEncoding(encoding) != nullptr; }

std::string supportedEncodings() {
  std::string list;
  for (const auto& info : kEncodings) {
    list += list.empty() ? "" : ", ";
    list += info.name;
  }
  return list;
}

ImageFrame fromImageMessage(const sensor_msgs::Image& message,
                            const boost::shared_ptr<void const>& tracked_object) {
  const EncodingInfo* info = findEncoding(message.encoding);
  if (info == nullptr) {
    throw std::invalid_argument("unsupported encoding '" + message.encoding + "' (supported: " +
                                supportedEncodings() + ")");
  }
  if (message.width == 0 || message.height == 0) {
    throw std::invalid_argument("empty image (" + std::to_string(message.width) + " x " +
                                std::to_string(message.height) + " px)");
  }
  // cv_bridge trusts width, height and step; a malformed message must not make it read past data.
  const std::size_t row_bytes = static_cast<std::size_t>(message.width) * info->bytes_per_pixel;
  if (message.step < row_bytes) {
    throw std::invalid_argument("step " + std::to_string(message.step) + " is less than width " +
                                std::to_string(message.width) + " x " +
                                std::to_string(info->bytes_per_pixel) + " bytes of " + message.encoding);
  }
  const std::size_t needed = static_cast<std::size_t>(message.step) * message.height;
  if (message.data.size() < needed) {
    throw std::invalid_argument("data holds " + std::to_string(message.data.size()) +
                                " bytes, but step x height needs " + std::to_string(needed));
  }

  ImageFrame frame;
  frame.order = info->order;
  try {
    // Keeps the encoding; cv_bridge copies (and swaps bytes) only for big-endian 16-bit data.
    frame.cv_image = cv_bridge::toCvShare(message, tracked_object);
  } catch (const cv_bridge::Exception& error) {
    throw std::invalid_argument(std::string("cv_bridge: ") + error.what());
  }
  return frame;
}

cv::Mat describeImage(const DescriptorExtractor& extractor, const sensor_msgs::Image& message,
                      const boost::shared_ptr<void const>& tracked_object) {
  const ImageFrame frame = fromImageMessage(message, tracked_object);
  return extractor.compute(frame.image(), frame.order);
}

}  // namespace node
}  // namespace mrs_vpr
