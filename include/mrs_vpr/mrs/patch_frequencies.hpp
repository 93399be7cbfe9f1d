#pragma once

#include <cstdint>
#include <vector>

#include "mrs_vpr/mrs/compact_cells.hpp"

namespace mrs_vpr {

/**
 * The compact cells of the thumbnail front end: for every normalisation patch of a descriptor, its
 * three lowest 2-D DCT frequencies (horizontal, vertical and both: the 2 x 2 lowest without the
 * mean, which patch normalisation sets to 0), one byte each. A 64 x 32 descriptor with 8 x 8 patches
 * gives 96-byte cells, 1/21 of the descriptor and 3/16 of a cell pooled over runs of 4 pixels.
 *
 * The basis is fixed, so cells need no fitting to a map, never change as the map grows and mean
 * the same in every map. On the tune half of the real benchmark (M = 9137, N = 300, stride 4; N =
 * 200, stride 2) the coarse table of these cells put the true place first in every query, as
 * 512-byte pixel-pooled cells did; 2 frequencies (64 bytes) 95%, runs of 16 or 32 pixels (128 or
 * 64 bytes) 88% and 84%, the map's first 64 principal components 82-88% (doc/paper_gaps.md).
 *
 * A cell of stride s is the transform of the mean of the s frames ending at its frame (clipped to
 * the frames that exist), as temporal_pooling.hpp pools; the transform is linear, so this is also
 * the mean of the frames' transforms.
 */
class PatchFrequencies : public CompactCells {
 public:
  /// Frequencies kept per patch.
  static constexpr int kPerPatch = 3;

  /// Cells of thumbnails of this geometry (image_width, image_height, patch_size). Throws
  /// std::invalid_argument when it is invalid or not a thumbnail's.
  explicit PatchFrequencies(const DescriptorParams& geometry);

  /// Bytes per cell: kPerPatch per patch.
  int cellSize() const override;
  void project(const std::uint16_t* sums, int frames, std::uint8_t* cell) const override;

 private:
  std::vector<float> wave_;  ///< The first cosine of the patch's DCT, sample x of a patch row.
};

}  // namespace mrs_vpr
