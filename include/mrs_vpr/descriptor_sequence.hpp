#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

namespace mrs_vpr {

/// Non-owning view of `count` consecutive descriptors of `descriptor_size` bytes each.
struct SequenceView {
  const std::uint8_t* data = nullptr;
  int count = 0;
  int descriptor_size = 0;

  const std::uint8_t* frame(int index) const {
    return data + static_cast<std::ptrdiff_t>(index) * descriptor_size;
  }
  /// Frames [begin, end) of this view. Throws std::out_of_range when the range is invalid.
  SequenceView slice(int begin, int end) const;
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
  void clear();

  int size() const { return static_cast<int>(stamps_.size()); }
  bool empty() const { return stamps_.empty(); }
  int descriptorSize() const { return descriptor_size_; }
  const std::uint8_t* descriptor(int index) const;
  double stamp(int index) const { return stamps_.at(static_cast<std::size_t>(index)); }
  /// Bytes held by descriptors and stamps (capacity, not just size).
  std::size_t memoryBytes() const;

  SequenceView view() const { return {data_.data(), size(), descriptor_size_}; }
  SequenceView view(int begin, int end) const { return view().slice(begin, end); }

 private:
  int descriptor_size_;
  std::vector<std::uint8_t> data_;
  std::vector<double> stamps_;
};

/// The reference map is a descriptor sequence that only grows (or is reset).
using ReferenceMap = DescriptorSequence;

}  // namespace mrs_vpr
