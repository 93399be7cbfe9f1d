#include "mrs_vpr/front_end/thumbnail_front_end.hpp"

#include <opencv2/imgproc.hpp>

namespace mrs_vpr {

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

ThumbnailFrontEnd::ThumbnailFrontEnd(const DescriptorParams& params) : params_(params) {}

cv::Mat ThumbnailFrontEnd::describeGrey(const cv::Mat& grey) const {
  // A camera sends frames of one size: buffers kept per thread are reused, so that describing a
  // 640 x 480 frame does not fault in a fresh 1.2 MB float image every time.
  thread_local cv::Mat full;
  thread_local cv::Mat small;
  grey.convertTo(full, CV_32F);
  cv::resize(full, small, cv::Size(params_.image_width, params_.image_height), 0.0, 0.0, cv::INTER_AREA);
  normalisePatches(small, params_.patch_size);
  cv::Mat descriptor;
  // 128 + 32 z, saturated to [0, 255]: +-4 std in steps of 1/32 std.
  small.convertTo(descriptor, CV_8U, kLevelsPerStd, 128.0);
  return descriptor.reshape(1, 1);  // convertTo allocated it: continuous and owned.
}

cv::Mat ThumbnailFrontEnd::picture(const std::uint8_t* descriptor) const {
  return cv::Mat(params_.image_height, params_.image_width, CV_8UC1, const_cast<std::uint8_t*>(descriptor)).clone();
}

}  // namespace mrs_vpr
