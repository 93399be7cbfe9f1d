#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

namespace mrs_vpr {

/// Pooled cells (see temporal_pooling.hpp) that a store keeps for strides 2, 4, ..., so that a
/// coarse-to-fine search need not pool the whole map for every query.
struct PooledCells {
  int pixel_pooling = 1;
  /// levels[i]: the cells of stride 2^(i+1), cell J ending at frame J * stride, each
  /// descriptor_size / pixel_pooling bytes.
  std::vector<std::vector<std::uint8_t>> levels;
};

/// Non-owning view of `count` descriptors of `descriptor_size` bytes each, `step` frames apart in
/// the underlying store (step > 1 is a temporally subsampled sequence).
struct SequenceView {
  const std::uint8_t* data = nullptr;
  int count = 0;
  int descriptor_size = 0;
  int step = 1;
  /// Cells kept by the store, or null. Only a view that starts at the store's first frame has them
  /// (cells look back only, so any prefix of the store can use them).
  const PooledCells* pooled = nullptr;

  const std::uint8_t* frame(int index) const {
    return data + static_cast<std::ptrdiff_t>(index) * step * descriptor_size;
  }
  /// Frames [begin, end) of this view. Throws std::out_of_range when the range is invalid.
  SequenceView slice(int begin, int end) const;
  /// Every `stride`-th frame of this view, starting at `first`. Throws std::out_of_range.
  SequenceView subsample(int first, int stride) const;
  /// The store's pooled cells of `stride` and `pixel_pooling` for this view (cells 0 ..
  /// (count - 1) / stride), or an empty view when the store does not keep them.
  SequenceView pooledCells(int stride, int pixel_pooling) const;
};

/**
 * Append-only store of descriptors and their time stamps, frames 0..size()-1, kept in one contiguous
 * block so that a search streams through memory. Used both as the reference map and for test
 * sequences.
 */
class DescriptorSequence {
 public:
  explicit DescriptorSequence(int descriptor_size);

  /// Appends a 1 x descriptor_size CV_8UC1 row. Throws std::invalid_argument on a size or type mismatch.
  void append(const cv::Mat& descriptor, double stamp = 0.0);
  void reserve(int frames);
  /// Forgets every frame (the pooling stride stays).
  void clear();

  /// Also keeps the pooled cells of strides 2, 4, ..., 2^levels and `pixel_pooling` (see
  /// temporal_pooling.hpp), updated on every append. Costs under 1 / pixel_pooling of the
  /// descriptors' memory. levels == 0 stops keeping them. Throws std::invalid_argument when
  /// pixel_pooling does not divide the descriptor size.
  void keepPooledCells(int levels, int pixel_pooling);

  int size() const { return static_cast<int>(stamps_.size()); }
  bool empty() const { return stamps_.empty(); }
  int descriptorSize() const { return descriptor_size_; }
  const std::uint8_t* descriptor(int index) const;
  double stamp(int index) const { return stamps_.at(static_cast<std::size_t>(index)); }
  /// Bytes held by descriptors and stamps (capacity, not just size).
  std::size_t memoryBytes() const;

  SequenceView view() const;
  SequenceView view(int begin, int end) const { return view().slice(begin, end); }

 private:
  int descriptor_size_;
  std::vector<std::uint8_t> data_;
  std::vector<double> stamps_;
  PooledCells pooled_;

  void appendPooledCells(int last);
};

/// The reference map is a descriptor sequence that only grows (or is reset).
using ReferenceMap = DescriptorSequence;

}  // namespace mrs_vpr
