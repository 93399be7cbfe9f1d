#include "mrs_vpr/descriptor.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

namespace mrs_vpr {

cv::Mat toGrayFloat(const cv::Mat& image, ChannelOrder order) {
  if (image.empty()) {
    throw std::invalid_argument("image is empty (0 x 0)");
  }
  const bool rgb = order == ChannelOrder::kRgb;
  cv::Mat gray;
  switch (image.type()) {
    case CV_8UC1:
    case CV_16UC1:
      gray = image;
      break;
    case CV_8UC3:
      cv::cvtColor(image, gray, rgb ? cv::COLOR_RGB2GRAY : cv::COLOR_BGR2GRAY);
      break;
    case CV_8UC4:
      cv::cvtColor(image, gray, rgb ? cv::COLOR_RGBA2GRAY : cv::COLOR_BGRA2GRAY);
      break;
    default:
      throw std::invalid_argument("unsupported image type " + cv::typeToString(image.type()) +
                                  " (supported: 8UC1, 16UC1, 8UC3, 8UC4)");
  }
  cv::Mat result;
  gray.convertTo(result, CV_32F);
  return result;
}

void normalisePatches(cv::Mat& image, int patch_size) {
  CV_Assert(image.type() == CV_32FC1);
  for (int y = 0; y + patch_size <= image.rows; y += patch_size) {
    for (int x = 0; x + patch_size <= image.cols; x += patch_size) {
      cv::Mat patch = image(cv::Rect(x, y, patch_size, patch_size));
      cv::Scalar mean;
      cv::Scalar std_dev;
      cv::meanStdDev(patch, mean, std_dev);
      if (std_dev[0] > 1e-6) {
        patch.convertTo(patch, CV_32F, 1.0 / std_dev[0], -mean[0] / std_dev[0]);
      } else {
        patch.setTo(0.0F);
      }
    }
  }
}

DescriptorExtractor::DescriptorExtractor(const DescriptorParams& params) : params_(params) {
  params_.validate();
}

cv::Mat DescriptorExtractor::compute(const cv::Mat& image, ChannelOrder order) const {
  if (static_cast<long long>(image.total()) > kMaxImagePixels) {
    throw std::invalid_argument("image of " + std::to_string(image.cols) + " x " + std::to_string(image.rows) +
                                " pixels is larger than the " + std::to_string(kMaxImagePixels) + " pixels allowed");
  }
  cv::Mat gray = toGrayFloat(image, order);
  cv::Mat small;
  cv::resize(gray, small, cv::Size(params_.image_width, params_.image_height), 0.0, 0.0, cv::INTER_AREA);
  normalisePatches(small, params_.patch_size);
  cv::Mat descriptor;
  // 128 + 32 z, saturated to [0, 255]: +-4 std in steps of 1/32 std.
  small.convertTo(descriptor, CV_8U, kLevelsPerStd, 128.0);
  return descriptor.reshape(1, 1);  // convertTo allocated it: continuous and owned.
}

}  // namespace mrs_vpr
