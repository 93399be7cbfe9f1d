#pragma once

#include <opencv2/core.hpp>

#include "mrs_vpr/parameters.hpp"

namespace mrs_vpr {

/// Channel order of a 3- or 4-channel image (ROS bgr8/bgra8 vs rgb8/rgba8).
enum class ChannelOrder { kBgr, kRgb };

/**
 * SeqSLAM image descriptor: grayscale -> resize to W x H (area interpolation) -> patch normalisation.
 *
 * Each patch is brought to zero mean and unit standard deviation, as OpenSeqSLAM does, but the
 * result is kept at a fine resolution instead of OpenSeqSLAM's integer rounding: the z-score is stored
 * as uint8 `128 + round(32 * z)` (saturated at +-4 std). One byte per pixel keeps a million-frame map
 * in 2 GB and lets the difference be an integer SIMD sum of absolute differences.
 */
class DescriptorExtractor {
 public:
  /// Quantisation steps per standard deviation of a patch.
  static constexpr float kLevelsPerStd = 32.0F;
  /// The largest image described [pixels], 6000 x 4000 and more: describing converts the image to
  /// floats, about 12 bytes a pixel, and one request must not be able to exhaust memory.
  static constexpr long long kMaxImagePixels = 25000000;

  /// Throws std::invalid_argument when the parameters are invalid.
  explicit DescriptorExtractor(const DescriptorParams& params);

  /**
   * Describes one image: CV_8UC1, CV_16UC1, CV_8UC3 or CV_8UC4 of any size.
   * Returns a continuous 1 x (W*H) CV_8UC1 row.
   * Throws std::invalid_argument for an empty image, an unsupported type or an image of more than
   * kMaxImagePixels pixels.
   */
  cv::Mat compute(const cv::Mat& image, ChannelOrder order = ChannelOrder::kBgr) const;

  /// Bytes per descriptor (W * H).
  int size() const { return params_.image_width * params_.image_height; }

  const DescriptorParams& params() const { return params_; }

 private:
  DescriptorParams params_;
};

/// Grayscale float image of any supported type (see DescriptorExtractor::compute).
cv::Mat toGrayFloat(const cv::Mat& image, ChannelOrder order);

/// Normalises every patch_size x patch_size patch of a CV_32FC1 image in place to zero mean, unit std
/// (population std). A constant patch becomes all zeros.
void normalisePatches(cv::Mat& image, int patch_size);

}  // namespace mrs_vpr
