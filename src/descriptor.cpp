#include "mrs_vpr/descriptor.hpp"

#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

namespace mrs_vpr {

const cv::Mat& toGrey(const cv::Mat& image, ChannelOrder order, cv::Mat& buffer) {
  if (image.empty()) {
    throw std::invalid_argument("image is empty (0 x 0)");
  }
  const bool rgb = order == ChannelOrder::kRgb;
  switch (image.type()) {
    case CV_8UC1:
    case CV_16UC1:
      return image;
    case CV_8UC3:
      cv::cvtColor(image, buffer, rgb ? cv::COLOR_RGB2GRAY : cv::COLOR_BGR2GRAY);
      return buffer;
    case CV_8UC4:
      cv::cvtColor(image, buffer, rgb ? cv::COLOR_RGBA2GRAY : cv::COLOR_BGRA2GRAY);
      return buffer;
    default:
      throw std::invalid_argument("unsupported image type " + cv::typeToString(image.type()) +
                                  " (supported: 8UC1, 16UC1, 8UC3, 8UC4)");
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
