#include "mrs_vpr/node/image_conversion.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

namespace mrs_vpr {
namespace node {
namespace {

/// Pixels that the descriptor reads as they are.
constexpr int kAsTheyAre = -1;

struct EncodingInfo {
  const char* name;
  int bytes_per_pixel;
  ChannelOrder order;
  int cv_type;
  /// The cv::cvtColor code that makes grey of the rest: a camera's raw mosaic or its YUV.
  int to_grey = kAsTheyAre;
  /// Pixels that share one group of bytes: YUV 4:2:2 sends two pixels' luma with one chroma pair.
  unsigned pixels_per_group = 1;
};

const std::array<EncodingInfo, 23> kEncodings{{
    {"mono8", 1, ChannelOrder::kBgr, CV_8UC1},
    {"mono16", 2, ChannelOrder::kBgr, CV_16UC1},
    {"bgr8", 3, ChannelOrder::kBgr, CV_8UC3},
    {"rgb8", 3, ChannelOrder::kRgb, CV_8UC3},
    {"bgra8", 4, ChannelOrder::kBgr, CV_8UC4},
    {"rgba8", 4, ChannelOrder::kRgb, CV_8UC4},
    {"bgr16", 6, ChannelOrder::kBgr, CV_16UC3},
    {"rgb16", 6, ChannelOrder::kRgb, CV_16UC3},
    {"bgra16", 8, ChannelOrder::kBgr, CV_16UC4},
    {"rgba16", 8, ChannelOrder::kRgb, CV_16UC4},
    // What many cameras' drivers publish as image_raw: demosaiced straight to grey, which is all that
    // the front ends read, so that no image_proc node is needed in front of this one.
    {"bayer_rggb8", 1, ChannelOrder::kBgr, CV_8UC1, cv::COLOR_BayerRGGB2GRAY},
    {"bayer_bggr8", 1, ChannelOrder::kBgr, CV_8UC1, cv::COLOR_BayerBGGR2GRAY},
    {"bayer_gbrg8", 1, ChannelOrder::kBgr, CV_8UC1, cv::COLOR_BayerGBRG2GRAY},
    {"bayer_grbg8", 1, ChannelOrder::kBgr, CV_8UC1, cv::COLOR_BayerGRBG2GRAY},
    {"bayer_rggb16", 2, ChannelOrder::kBgr, CV_16UC1, cv::COLOR_BayerRGGB2GRAY},
    {"bayer_bggr16", 2, ChannelOrder::kBgr, CV_16UC1, cv::COLOR_BayerBGGR2GRAY},
    {"bayer_gbrg16", 2, ChannelOrder::kBgr, CV_16UC1, cv::COLOR_BayerGBRG2GRAY},
    {"bayer_grbg16", 2, ChannelOrder::kBgr, CV_16UC1, cv::COLOR_BayerGRBG2GRAY},
    // USB cameras (usb_cam): "yuv422" is UYVY, "yuv422_yuy2" YUYV; grey is their luma.
    {"yuv422", 2, ChannelOrder::kBgr, CV_8UC2, cv::COLOR_YUV2GRAY_UYVY, 2},
    {"yuv422_yuy2", 2, ChannelOrder::kBgr, CV_8UC2, cv::COLOR_YUV2GRAY_YUY2, 2},
    // OpenCV's own types, which cv_bridge's cv2_to_imgmsg and CvImage publish for an image without a
    // named encoding: read as OpenCV's images are, grey, and colour in its blue-first order (cv_bridge
    // passes them on as they are). 16UC1 is left out: depth cameras publish it, and depth is no view.
    {"8UC1", 1, ChannelOrder::kBgr, CV_8UC1},
    {"8UC3", 3, ChannelOrder::kBgr, CV_8UC3},
    {"8UC4", 4, ChannelOrder::kBgr, CV_8UC4},
}};

bool hostIsBigEndian() {
  const std::uint16_t probe = 1;
  return *reinterpret_cast<const std::uint8_t*>(&probe) == 0;
}

/// A copy of 16-bit `image` with the bytes of every value swapped (a message of the other endianness).
cv::Mat swapBytes(const cv::Mat& image) {
  cv::Mat swapped = image.clone();
  for (int row = 0; row < swapped.rows; ++row) {
    auto* value = swapped.ptr<std::uint16_t>(row);
    for (int i = 0; i < swapped.cols * swapped.channels(); ++i) {
      value[i] = static_cast<std::uint16_t>((value[i] >> 8) | (value[i] << 8));
    }
  }
  return swapped;
}

const EncodingInfo* findEncoding(const std::string& encoding) {
  for (const auto& info : kEncodings) {
    if (encoding == info.name) {
      return &info;
    }
  }
  return nullptr;
}

}  // namespace

int bayerToGreyCode(const std::string& encoding) {
  const EncodingInfo* info = findEncoding(encoding);
  const bool bayer = info != nullptr && encoding.rfind("bayer_", 0) == 0;
  return bayer ? info->to_grey : kAsTheyAre;
}

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
    const std::string depth_hint = message.encoding == "16UC1" || message.encoding == "32FC1"
                                       ? "; a depth camera's image is not a view of a place, and a grey camera "
                                         "is published as mono8 or mono16"
                                       : "";
    throw std::invalid_argument("unsupported encoding '" + message.encoding + "' (supported: " +
                                supportedEncodings() + ")" + depth_hint);
  }
  if (message.width == 0 || message.height == 0) {
    throw std::invalid_argument("empty image (" + std::to_string(message.width) + " x " +
                                std::to_string(message.height) + " px)");
  }
  if (message.width % info->pixels_per_group != 0) {
    throw std::invalid_argument(message.encoding + " sends pixels in groups of " +
                                std::to_string(info->pixels_per_group) + ", so its width must be a multiple of " +
                                std::to_string(info->pixels_per_group) + ", got " + std::to_string(message.width));
  }
  // The frame trusts width, height and step; a malformed message must not make it read past data.
  const std::size_t row_bytes = static_cast<std::size_t>(message.width) * info->bytes_per_pixel;
  if (message.step < row_bytes) {
    throw std::invalid_argument("step " + std::to_string(message.step) + " is less than width " +
                                std::to_string(message.width) + " x " +
                                std::to_string(info->bytes_per_pixel) + " bytes of " + message.encoding);
  }
  const auto value_bytes = static_cast<std::uint32_t>(CV_ELEM_SIZE1(info->cv_type));
  if (message.step % value_bytes != 0) {
    throw std::invalid_argument("step " + std::to_string(message.step) + " is not a whole number of the " +
                                std::to_string(value_bytes) + "-byte values of " + message.encoding);
  }
  const std::size_t needed = static_cast<std::size_t>(message.step) * message.height;
  if (message.data.size() < needed) {
    throw std::invalid_argument("data holds " + std::to_string(message.data.size()) +
                                " bytes, but step x height needs " + std::to_string(needed));
  }

  ImageFrame frame;
  frame.order = info->order;
  // Keeps the encoding and shares the message's pixels, as cv_bridge::toCvShare does (without
  // cv_bridge, whose image codecs would load ~120 libraries into every tool); only 16-bit data of the
  // other byte order is copied.
  const cv::Mat shared(static_cast<int>(message.height), static_cast<int>(message.width), info->cv_type,
                       const_cast<std::uint8_t*>(message.data.data()), message.step);
  const bool swapped = CV_MAT_DEPTH(info->cv_type) == CV_16U && (message.is_bigendian != 0) != hostIsBigEndian();
  const cv::Mat pixels = swapped ? swapBytes(shared) : shared;
  if (info->to_grey != kAsTheyAre) {
    cv::cvtColor(pixels, frame.pixels, info->to_grey);  // A grey copy: the message is not kept.
  } else {
    frame.pixels = pixels;
    if (!swapped) frame.owner = tracked_object;
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
