#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include <boost/make_shared.hpp>
#include <opencv2/core.hpp>
#include <sensor_msgs/Image.h>

namespace mrs_vpr {
namespace bag {

/// An image message holding a copy of `image` (rows packed, native byte order), as cv_bridge's
/// CvImage::toImageMsg makes it; without cv_bridge, whose codecs would load ~120 libraries at start-up.
/// Inline: both the bag library and the bag reader plugin (which does not link it) make messages.
inline sensor_msgs::ImagePtr imageMessageOf(const cv::Mat& image, const std::string& encoding,
                                            const std_msgs::Header& header) {
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

}  // namespace bag
}  // namespace mrs_vpr
