#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "mrs_vpr/parameters.hpp"
#include "mrs_vpr/stamp.hpp"

namespace mrs_vpr {

class CompactCells;

/// The compact cells of MRS's coarse levels (see mrs/compact_cells.hpp) that a store keeps for
/// strides 1, 2, 4, ..., so that a coarse-to-fine search need not transform the whole map per query.
struct CoarseCells {
  std::shared_ptr<const CompactCells> kind;
  /// Each frame's own cell (stride 1): the first pass of a short test sequence
  /// (mrs/short_sequence_search.hpp).
  std::vector<std::uint8_t> frames;
  /// levels[i]: the cells of stride 2^(i+1), cell J ending at frame J * stride.
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
  const CoarseCells* coarse = nullptr;

  /// Bytes from one frame of the view to the next.
  std::ptrdiff_t pitch() const { return static_cast<std::ptrdiff_t>(step) * descriptor_size; }
  const std::uint8_t* frame(int index) const { return data + index * pitch(); }
  /// Frames [begin, end) of this view. Throws std::out_of_range when the range is invalid.
  SequenceView slice(int begin, int end) const;
  /// Every `stride`-th frame of this view, starting at `first`. Throws std::out_of_range.
  SequenceView subsample(int first, int stride) const;
  /// The store's coarse cells of `stride` for this view (cells 0 .. (count - 1) / stride), or an
  /// empty view when the store does not keep them or keeps them for another front end.
  SequenceView coarseCells(int stride, const DescriptorParams& geometry) const;
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
  void append(const cv::Mat& descriptor, Stamp stamp = Stamp());
  void reserve(int frames);
  /// Forgets every frame and its cells; the kind of cells kept stays.
  void clear();

  /// Also keeps MRS's compact cells of strides 1, 2, 4, ..., 2^levels for descriptors of `geometry`
  /// (see mrs/compact_cells.hpp), updated on every append: 180 bytes a frame for 96-byte cells and
  /// 3 levels (96 + 48 + 24 + 12). levels == 0 stops keeping them. Throws std::invalid_argument
  /// when the geometry is invalid or does not give this sequence's descriptor size.
  void keepCoarseCells(int levels, const DescriptorParams& geometry);

  int size() const { return static_cast<int>(stamps_.size()); }
  bool empty() const { return stamps_.empty(); }
  int descriptorSize() const { return descriptor_size_; }
  const std::uint8_t* descriptor(int index) const;
  /// The same frame as a 1 x descriptorSize() CV_8UC1 header over the stored bytes: no copy, valid
  /// until the next append, for reading only (clone() it to keep or change it).
  cv::Mat descriptorRow(int index) const;
  Stamp stamp(int index) const { return stamps_.at(static_cast<std::size_t>(index)); }
  /// Bytes held by descriptors, stamps and coarse cells (capacity, not just size).
  std::size_t memoryBytes() const;

  SequenceView view() const;
  SequenceView view(int begin, int end) const { return view().slice(begin, end); }

 private:
  int descriptor_size_;
  std::vector<std::uint8_t> data_;
  std::vector<Stamp> stamps_;
  CoarseCells coarse_;

  void appendCoarseCells(int last);
  /// Shrinks every array to its first `frames` frames (never grows them, so it cannot throw).
  void trimTo(int frames);
};

/// Throws std::invalid_argument unless `descriptor` is `bytes` continuous bytes of CV_8UC1 (a front
/// end's descriptor), naming what it is instead; `what` names the descriptor in the message.
void requireDescriptorBytes(const cv::Mat& descriptor, int bytes, const std::string& what = "a descriptor");

}  // namespace mrs_vpr
