#include "mrs_vpr/lazy_difference_matrix.hpp"

#include <algorithm>

#include "mrs_vpr/contrast_enhancement.hpp"
#include "mrs_vpr/difference_matrix.hpp"

namespace mrs_vpr {
namespace {

std::uint64_t key(int row, int column) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(row)) << 32U) |
         static_cast<std::uint32_t>(column);
}

}  // namespace

LazyDifferenceMatrix::LazyDifferenceMatrix(SequenceView query, SequenceView reference, int contrast_window)
    : query_(query), reference_(reference), contrast_window_(contrast_window) {
  setLevel(1, query.count - 1);
}

void LazyDifferenceMatrix::setLevel(int stride, int anchor) {
  stride_ = stride;
  anchor_ = anchor;
  grid_size_ = (reference_.count + stride - 1) / stride;
  enhanced_.clear();
}

float LazyDifferenceMatrix::raw(int test_frame, int reference_frame) {
  const auto [it, inserted] = raw_.try_emplace(key(test_frame, reference_frame), 0.0F);
  if (inserted) {
    it->second = descriptorDifference(query_.frame(test_frame), reference_.frame(reference_frame),
                                      query_.descriptor_size);
    ++comparisons_;
  }
  return it->second;
}

float LazyDifferenceMatrix::enhanced(int k, int grid_index) {
  const auto [it, inserted] = enhanced_.try_emplace(key(k, grid_index), 0.0F);
  if (!inserted) return it->second;
  const int test_frame = anchor_ + k * stride_;
  if (contrast_window_ == 0) {
    it->second = raw(test_frame, grid_index * stride_);
    return it->second;
  }
  // The same window as enhanceContrast, on this level's grid.
  const int half = contrast_window_ / 2;
  const int begin = std::max(0, grid_index - half);
  const int end = std::min(grid_size_, grid_index + half + 1);
  window_.clear();
  for (int j = begin; j < end; ++j) window_.push_back(raw(test_frame, j * stride_));
  const float centre = window_[static_cast<std::size_t>(grid_index - begin)];
  it->second = enhanceCell(centre, window_.data(), static_cast<int>(window_.size()), contrast_window_);
  return it->second;
}

}  // namespace mrs_vpr
