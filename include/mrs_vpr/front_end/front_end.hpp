#pragma once

#include <cstdint>
#include <memory>

#include <opencv2/core.hpp>

#include "mrs_vpr/parameters.hpp"

namespace mrs_vpr {

/**
 * How a grey image becomes a descriptor: a row of bytes that the search compares by their mean
 * absolute difference. Every front end quantises its values to one byte, so that the map, the
 * difference kernels and MRS's pooled levels are the same for all of them.
 */
class FrontEnd {
 public:
  virtual ~FrontEnd() = default;

  /// The descriptor (a continuous 1 x size() CV_8UC1 row, owned) of a CV_8UC1 or CV_16UC1 image.
  virtual cv::Mat describeGrey(const cv::Mat& grey) const = 0;
  /// Bytes per descriptor.
  virtual int size() const = 0;
  /// A grey picture (CV_8UC1) of what a descriptor keeps of its image, for the debug image.
  virtual cv::Mat picture(const std::uint8_t* descriptor) const = 0;
};

/// The front end `params` chooses. Throws std::invalid_argument when the parameters are invalid.
std::unique_ptr<const FrontEnd> makeFrontEnd(const DescriptorParams& params);

}  // namespace mrs_vpr
