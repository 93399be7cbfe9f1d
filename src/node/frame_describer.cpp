#include "mrs_vpr/node/frame_describer.hpp"

#include <opencv2/imgproc.hpp>

namespace mrs_vpr {
namespace node {

cv::Mat FrameDescriber::describe(const cv::Mat& image, ChannelOrder order) {
  const int type = image.type();
  const bool supported = type == CV_8UC1 || type == CV_16UC1 || type == CV_8UC3 || type == CV_8UC4;
  if (image.empty() || !supported || static_cast<long long>(image.total()) > DescriptorExtractor::kMaxImagePixels) {
    return extractor_.compute(image, order);  // throws, with the core's message
  }
  // The steps of DescriptorExtractor::compute, into buffers that OpenCV reuses when the size repeats.
  std::lock_guard<std::mutex> lock(mutex_);
  const bool rgb = order == ChannelOrder::kRgb;
  const cv::Mat* gray = &image;
  if (type == CV_8UC3) {
    cv::cvtColor(image, gray_, rgb ? cv::COLOR_RGB2GRAY : cv::COLOR_BGR2GRAY);
    gray = &gray_;
  } else if (type == CV_8UC4) {
    cv::cvtColor(image, gray_, rgb ? cv::COLOR_RGBA2GRAY : cv::COLOR_BGRA2GRAY);
    gray = &gray_;
  }
  gray->convertTo(float_, CV_32F);
  const DescriptorParams& params = extractor_.params();
  cv::resize(float_, small_, cv::Size(params.image_width, params.image_height), 0.0, 0.0, cv::INTER_AREA);
  normalisePatches(small_, params.patch_size);
  cv::Mat descriptor;
  small_.convertTo(descriptor, CV_8U, DescriptorExtractor::kLevelsPerStd, 128.0);
  return descriptor.reshape(1, 1);
}

}  // namespace node
}  // namespace mrs_vpr
