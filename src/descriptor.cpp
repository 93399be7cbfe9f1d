#include "mrs_vpr/descriptor.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

namespace mrs_vpr {
namespace {

/// OpenCV hands a colour conversion of more than 2^16 pixels to its thread pool. For one camera frame
/// waking the pool costs more CPU than the conversion itself (640 x 480: 0.42 ms of CPU against 0.15
/// ms on the calling thread alone, at 30 Hz), so a frame is converted in bands below that size, each
/// on the calling thread. The pixels are the same as one call's.
constexpr int kPixelsPerBand = 1 << 16;

void convertInBands(const cv::Mat& colour, int code, cv::Mat& grey) {
  const cv::Mat image = colour;  // Shares the pixels: `grey` may be `colour` itself, reallocated below.
  // Of the colour's depth: a band of another type would be reallocated by cvtColor rather than written,
  // and `grey` would keep the pixels last written into it.
  grey.create(image.rows, image.cols, CV_MAKETYPE(image.depth(), 1));
  const int band_rows = std::max(1, kPixelsPerBand / image.cols);
  for (int top = 0; top < image.rows; top += band_rows) {
    const int bottom = std::min(image.rows, top + band_rows);
    cv::Mat band = grey.rowRange(top, bottom);
    cv::cvtColor(image.rowRange(top, bottom), band, code);
  }
}

}  // namespace

const cv::Mat& toGrey(const cv::Mat& image, ChannelOrder order, cv::Mat& buffer) {
  if (image.empty()) {
    throw std::invalid_argument("image is empty (0 x 0)");
  }
  if (image.dims != 2) {
    throw std::invalid_argument("image has " + std::to_string(image.dims) + " dimensions, not 2 (rows x columns)");
  }
  const bool rgb = order == ChannelOrder::kRgb;
  switch (image.type()) {
    case CV_8UC1:
    case CV_16UC1:
      return image;
    case CV_8UC3:
    case CV_16UC3:  // 16-bit colour PNGs; grey stays 16-bit, as a 16UC1 image is.
      convertInBands(image, rgb ? cv::COLOR_RGB2GRAY : cv::COLOR_BGR2GRAY, buffer);
      return buffer;
    case CV_8UC4:
    case CV_16UC4:
      convertInBands(image, rgb ? cv::COLOR_RGBA2GRAY : cv::COLOR_BGRA2GRAY, buffer);
      return buffer;
    default:
      throw std::invalid_argument("unsupported image type " + cv::typeToString(image.type()) +
                                  " (supported: 8UC1, 16UC1, 8UC3, 16UC3, 8UC4, 16UC4)");
  }
}

DescriptorExtractor::DescriptorExtractor(const DescriptorParams& params)
    : params_(params), front_end_(makeFrontEnd(params)) {}

cv::Mat DescriptorExtractor::compute(const cv::Mat& image, ChannelOrder order) const {
  if (static_cast<long long>(image.total()) > kMaxImagePixels) {
    throw std::invalid_argument("image of " + std::to_string(image.cols) + " x " + std::to_string(image.rows) +
                                " pixels is larger than the " + std::to_string(kMaxImagePixels) + " pixels allowed");
  }
  thread_local cv::Mat grey;  // Reused frame after frame; see compute's documentation.
  return front_end_->describeGrey(toGrey(image, order, grey));
}

}  // namespace mrs_vpr
