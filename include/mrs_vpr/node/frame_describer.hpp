#pragma once

#include <mutex>

#include <opencv2/core.hpp>

#include "mrs_vpr/descriptor.hpp"

namespace mrs_vpr {
namespace node {

/**
 * Describes camera frames as DescriptorExtractor::compute does, bit for bit, but keeps its
 * full-resolution grey and float images from one frame to the next. A camera sends frames of one
 * size, so after the first frame describing one allocates nothing but the descriptor: at 640 x 480,
 * 30 Hz, the fresh 1.2 MB float image of every frame cost more in page faults than all the arithmetic.
 * Thread-safe (frames are described one at a time).
 */
class FrameDescriber {
 public:
  /// Keeps a reference: `extractor` must outlive this object.
  explicit FrameDescriber(const DescriptorExtractor& extractor) : extractor_(extractor) {}

  /// The descriptor of `image` (a 1 x W*H CV_8UC1 row, owned). Throws std::invalid_argument as
  /// DescriptorExtractor::compute does, with its messages.
  cv::Mat describe(const cv::Mat& image, ChannelOrder order);

 private:
  const DescriptorExtractor& extractor_;
  std::mutex mutex_;
  cv::Mat gray_;   // full resolution, 8 or 16 bits
  cv::Mat float_;  // full resolution, CV_32F
  cv::Mat small_;  // descriptor size, CV_32F
};

}  // namespace node
}  // namespace mrs_vpr
