#pragma once

#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

#include "mrs_vpr/descriptor_sequence.hpp"

namespace mrs_vpr {

/**
 * Pooling, the low-pass filter of the coarse-to-fine search. A level of stride s compares "cells":
 * the mean descriptor of the s frames ending at a frame (frames end - s + 1 .. end, clipped to the
 * frames that exist), optionally also averaged over runs of `pixel_pooling` consecutive pixels.
 *
 * Subsampling alone (every s-th frame, as the paper writes) only works when s consecutive frames
 * look alike; on keyframed or fast imagery a coarse test frame meets a reference frame up to s/2
 * frames from its place and the coarse level sees nothing (measured on Nordland, N = 100 with two levels:
 * 57% success subsampled, 95.5% pooled). The mean of s frames still overlaps the mean of the matching s
 * frames when the alignment is off by a few frames. Cells only look back, so a cell never changes
 * once its last frame exists. Averaging runs of pixels (a lower horizontal resolution) makes the
 * exhaustive coarse level cheaper without costing accuracy (Nordland N = 300: 96% -> 98.5% with 4).
 */
void poolCell(SequenceView view, int end, int stride, int pixel_pooling, std::uint8_t* out);

/// Throws std::invalid_argument ("<name> P does not divide the descriptor size S") unless
/// pixel_pooling >= 1 divides descriptor_size.
void requirePixelPoolingDivides(int pixel_pooling, int descriptor_size, const std::string& name = "pixel pooling");

/// Cells ending at first_end, first_end + stride, ... (count of them), as a new sequence of
/// descriptors of view.descriptor_size / pixel_pooling bytes.
DescriptorSequence poolSequence(SequenceView view, int first_end, int stride, int count, int pixel_pooling = 1);

/// A sequence with the runs of `pixel_pooling` pixels of each frame summed once. Cells of any
/// stride then pool from these sums with contiguous additions only, so that pooling a test
/// sequence at every level of a search reads its full-size frames once rather than once per level.
class PixelRunSums {
 public:
  /// Throws std::invalid_argument when pixel_pooling does not divide the descriptor size.
  PixelRunSums(SequenceView view, int pixel_pooling);

  /// The same cells as poolSequence(view, first_end, stride, count, pixel_pooling).
  DescriptorSequence pool(int first_end, int stride, int count) const;

 private:
  std::uint16_t* frameSums(int frame) { return sums_.data() + static_cast<std::ptrdiff_t>(frame) * cell_size_; }
  const std::uint16_t* frameSums(int frame) const {
    return sums_.data() + static_cast<std::ptrdiff_t>(frame) * cell_size_;
  }

  int frames_;
  int pixel_pooling_;
  int cell_size_ = 0;
  std::vector<std::uint16_t> sums_;  ///< frames_ x cell_size_ run sums.
};

/// Cells ending at grid index J * stride of a reference: the store's kept cells when it has them,
/// else pooled on first use and remembered.
class PooledReference {
 public:
  PooledReference(SequenceView reference, int stride, int pixel_pooling = 1);

  /// Bytes per cell.
  int cellSize() const { return reference_.descriptor_size / pixel_pooling_; }
  /// Cells J = 0 .. size() - 1.
  int size() const { return (reference_.count - 1) / stride_ + 1; }
  const std::uint8_t* cell(int grid_index);

 private:
  SequenceView reference_;
  SequenceView kept_;
  int stride_;
  int pixel_pooling_;
  std::unordered_map<int, std::vector<std::uint8_t>> cells_;
};

}  // namespace mrs_vpr
