#pragma once

#include "mrs_vpr/front_end/front_end.hpp"

namespace mrs_vpr {

/**
 * OpenSeqSLAM's descriptor: the grey image resized to W x H (area interpolation), each patch brought
 * to zero mean and unit standard deviation.
 *
 * The result is kept at a finer resolution than OpenSeqSLAM's integer rounding: the z-score is stored
 * as uint8 `128 + round(32 * z)` (saturated at +-4 std), one byte a pixel.
 */
class ThumbnailFrontEnd : public FrontEnd {
 public:
  /// Quantisation steps per standard deviation of a patch.
  static constexpr float kLevelsPerStd = 32.0F;

  /// Uses the thumbnail fields of `params` (image_width, image_height, patch_size).
  explicit ThumbnailFrontEnd(const DescriptorParams& params);

  cv::Mat describeGrey(const cv::Mat& grey) const override;
  int size() const override { return params_.image_width * params_.image_height; }
  /// The descriptor itself, 128 + 32 z a pixel, is a viewable W x H grey image.
  cv::Mat picture(const std::uint8_t* descriptor) const override;

 private:
  DescriptorParams params_;
};

/// Normalises every patch_size x patch_size patch of a CV_32FC1 image in place to zero mean, unit std
/// (population std). A constant patch becomes all zeros.
void normalisePatches(cv::Mat& image, int patch_size);

}  // namespace mrs_vpr
