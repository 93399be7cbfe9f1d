#pragma once

#include <cstdint>
#include <memory>

#include <opencv2/core.hpp>

#include "mrs_vpr/front_end/front_end.hpp"
#include "mrs_vpr/parameters.hpp"

namespace mrs_vpr {

/// Channel order of a 3- or 4-channel image (ROS bgr8/bgra8 vs rgb8/rgba8).
enum class ChannelOrder { kBgr, kRgb };

/**
 * Describes images for the map and the search with the front end DescriptorParams::type chooses
 * (front_end/: HOG or OpenSeqSLAM's thumbnail): the image is turned grey, then described as one row
 * of bytes compared by their mean absolute difference.
 */
class DescriptorExtractor {
 public:
  /// Quantisation steps per unit of difference: descriptorDifference reports sums of absolute byte
  /// differences in these units (a thumbnail's patch standard deviations).
  static constexpr float kLevelsPerStd = 32.0F;
  /// The largest image described [pixels], 6000 x 4000 and more: describing converts the image to
  /// floats, about 12 bytes a pixel, and one request must not be able to exhaust memory.
  static constexpr long long kMaxImagePixels = 25000000;

  /// Throws std::invalid_argument when the parameters are invalid.
  explicit DescriptorExtractor(const DescriptorParams& params);

  /**
   * Describes one image: CV_8UC1, CV_16UC1, CV_8UC3, CV_16UC3, CV_8UC4 or CV_16UC4 of any size, strided or not.
   * Returns a continuous 1 x size() CV_8UC1 row. Buffers are kept per thread, so that a camera's
   * frames of one size allocate nothing but the descriptor.
   * Throws std::invalid_argument for an empty image, an unsupported type or an image of more than
   * kMaxImagePixels pixels.
   */
  cv::Mat compute(const cv::Mat& image, ChannelOrder order = ChannelOrder::kBgr) const;

  /// Bytes per descriptor.
  int size() const { return front_end_->size(); }
  /// A grey picture of what a descriptor keeps of its image (FrontEnd::picture).
  cv::Mat picture(const std::uint8_t* descriptor) const { return front_end_->picture(descriptor); }

  const DescriptorParams& params() const { return params_; }

 private:
  DescriptorParams params_;
  std::shared_ptr<const FrontEnd> front_end_;
};

/// The grey image (CV_8UC1 or CV_16UC1) of any supported type: `image` itself when it is grey, else
/// converted into `buffer`. Throws std::invalid_argument as DescriptorExtractor::compute does.
const cv::Mat& toGrey(const cv::Mat& image, ChannelOrder order, cv::Mat& buffer);

}  // namespace mrs_vpr
