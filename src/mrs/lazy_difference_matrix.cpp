#include "mrs_vpr/mrs/lazy_difference_matrix.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mrs_vpr/contrast_enhancement.hpp"
#include "mrs_vpr/difference_matrix.hpp"

namespace mrs_vpr {
namespace {

// Requests closer than this merge into one segment: filling a small gap is cheaper than bookkeeping.
constexpr int kMergeGap = 16;

}  // namespace

LazyDifferenceMatrix::LazyDifferenceMatrix(SequenceView query, SequenceView reference, int stride,
                                           const PatchFrequencies& frequencies, int contrast_window)
    : query_(query), reference_(reference, stride, frequencies), contrast_window_(contrast_window),
      segments_(static_cast<std::size_t>(query.count)) {}

const float* LazyDifferenceMatrix::rawRow(int row, int begin, int end) {
  std::vector<Segment>& segments = segments_[static_cast<std::size_t>(row)];
  for (const Segment& segment : segments) {
    if (segment.begin <= begin && segment.end() >= end) return segment.values.data() + (begin - segment.begin);
  }
  // Merge the request with every segment within reach into one new segment.
  const auto within_reach = [&](const Segment& segment) {
    return segment.begin <= end + kMergeGap && segment.end() + kMergeGap >= begin;
  };
  Segment merged;
  merged.begin = begin;
  int merged_end = end;
  for (const Segment& segment : segments) {
    if (within_reach(segment)) {
      merged.begin = std::min(merged.begin, segment.begin);
      merged_end = std::max(merged_end, segment.end());
    }
  }
  merged.values.assign(static_cast<std::size_t>(merged_end - merged.begin), std::numeric_limits<float>::quiet_NaN());
  for (const Segment& segment : segments) {
    if (within_reach(segment)) {
      std::copy(segment.values.begin(), segment.values.end(), merged.values.begin() + (segment.begin - merged.begin));
    }
  }
  segments.erase(std::remove_if(segments.begin(), segments.end(), within_reach), segments.end());
  const std::uint8_t* test_frame = query_.frame(row);
  for (int column = merged.begin; column < merged_end; ++column) {
    float& value = merged.values[static_cast<std::size_t>(column - merged.begin)];
    if (std::isnan(value)) {
      value = descriptorDifference(test_frame, reference_.cell(column), query_.descriptor_size);
      ++comparisons_;
    }
  }
  segments.push_back(std::move(merged));
  const Segment& result = segments.back();
  return result.values.data() + (begin - result.begin);
}

void LazyDifferenceMatrix::enhancedRow(int row, int begin, int end, float* out) {
  if (contrast_window_ == 0) {
    const float* raw = rawRow(row, begin, end);
    std::copy(raw, raw + (end - begin), out);
    return;
  }
  // The same clipped window as enhanceContrast.
  const int half = contrast_window_ / 2;
  const int raw_begin = std::max(0, begin - half);
  const int raw_end = std::min(columns(), end + half);
  const float* raw = rawRow(row, raw_begin, raw_end);
  // Prefix sums over the segment give every window's sums at once, instead of a pass per cell.
  const int length = raw_end - raw_begin;
  prefix_.resize(2 * (static_cast<std::size_t>(length) + 1));
  double* sums = prefix_.data();
  double* sums_of_squares = sums + length + 1;
  sums[0] = 0.0;
  sums_of_squares[0] = 0.0;
  for (int i = 0; i < length; ++i) {
    sums[i + 1] = sums[i] + raw[i];
    sums_of_squares[i + 1] = sums_of_squares[i] + static_cast<double>(raw[i]) * raw[i];
  }
  for (int column = begin; column < end; ++column) {
    const int low = std::max(0, column - half) - raw_begin;
    const int high = std::min(columns(), column + half + 1) - raw_begin;
    out[column - begin] = enhanceCellFromSums(raw[column - raw_begin], sums[high] - sums[low],
                                              sums_of_squares[high] - sums_of_squares[low], high - low, contrast_window_);
  }
}

}  // namespace mrs_vpr
