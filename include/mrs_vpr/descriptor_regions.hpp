#pragma once

#include <cstdint>
#include <vector>

#include "mrs_vpr/parameters.hpp"

namespace mrs_vpr {

/**
 * The regions each front end normalises on its own (HOG's blocks, the thumbnail's patches), and how
 * much two descriptors differ over them: the median region's mean absolute difference. A passer-by,
 * or noise that block normalisation amplifies in a textureless patch such as the sky, changes a few
 * regions, not the median one. Fixed by the front end's parameters, so copies share one.
 */
class DescriptorRegions {
 public:
  /// Throws std::invalid_argument when the front end's parameters are invalid.
  explicit DescriptorRegions(const DescriptorParams& front_end);

  /// The difference of descriptor `a` and a mean of descriptors `b` (descriptorSize() values each).
  double difference(const std::uint8_t* a, const float* b) const;
  /// The difference of two descriptors.
  double difference(const std::uint8_t* a, const std::uint8_t* b) const;

 private:
  /// The median over regions of `sums` (each region's summed absolute differences) by its bytes; `sums`
  /// becomes the means.
  double medianRegionMean(std::vector<double>& sums) const;

  /// Consecutive descriptor bytes [begin, end) of one region.
  struct Run {
    int begin;
    int end;
    int region;
  };

  std::vector<double> region_size_;  ///< Per region, its bytes.
  std::vector<Run> runs_;            ///< The descriptor's bytes as runs of one region each, in order.
};

}  // namespace mrs_vpr
