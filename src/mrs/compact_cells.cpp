#include "mrs_vpr/mrs/compact_cells.hpp"

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "mrs_vpr/difference_matrix.hpp"
#include "mrs_vpr/mrs/hog_cells.hpp"
#include "mrs_vpr/mrs/patch_frequencies.hpp"
#include "simd/vector_kernel.hpp"

namespace mrs_vpr {
namespace {

/// sum[i] = the sum of byte i of frames first .. last of `view` (descriptor_size values).
MRS_VPR_VECTOR_KERNEL
void sumFrames(SequenceView view, int first, int last, std::uint16_t* __restrict sum) {
  const int size = view.descriptor_size;
  std::fill(sum, sum + size, 0);
  // uint16 sums hold up to 257 frames of uint8; plain loops over restrict pointers vectorise.
  static_assert((1 << MrsParams::kMaxLevels) * 255 <= UINT16_MAX, "a coarsest cell's sums overflow 16 bits");
  for (int f = first; f <= last; ++f) {
    const std::uint8_t* __restrict frame = view.frame(f);
    for (int i = 0; i < size; ++i) sum[i] = static_cast<std::uint16_t>(sum[i] + frame[i]);
  }
}

}  // namespace

CompactCells::CompactCells(const DescriptorParams& geometry) : geometry_(geometry) { geometry_.validate(); }

void CompactCells::cell(SequenceView view, int end, int stride, std::uint8_t* out) const {
  const int first = std::max(0, end - stride + 1);
  const int last = std::min(end, view.count - 1);
  thread_local std::vector<std::uint16_t> sums;
  sums.resize(static_cast<std::size_t>(descriptorSize()));
  sumFrames(view, first, last, sums.data());
  project(sums.data(), last - first + 1, out);
}

DescriptorSequence CompactCells::cells(SequenceView view, int first_end, int stride, int count) const {
  requireDescriptorsOf(view);
  // Cells are independent: threads share them, each writing its own rows.
  cv::Mat rows(std::max(0, count), cellSize(), CV_8U);
  cv::parallel_for_(cv::Range(0, rows.rows), [&](const cv::Range& range) {
    for (int i = range.start; i < range.end; ++i) cell(view, first_end + i * stride, stride, rows.ptr(i));
  });
  DescriptorSequence result(cellSize());
  result.reserve(rows.rows);
  for (int i = 0; i < rows.rows; ++i) result.append(rows.row(i));
  return result;
}

void CompactCells::requireDescriptorsOf(SequenceView view) const {
  if (view.descriptor_size != descriptorSize()) {
    throw std::invalid_argument("MRS's coarse levels need descriptors of the " + geometry_.describe() + " front end, " +
                                std::to_string(descriptorSize()) + " bytes, got " +
                                std::to_string(view.descriptor_size));
  }
}

std::shared_ptr<const CompactCells> makeCompactCells(const DescriptorParams& params) {
  if (params.isHog()) return std::make_shared<const HogCells>(params);
  return std::make_shared<const PatchFrequencies>(params);
}

void cellDifferences(SequenceView query_cells, SequenceView reference, int stride, int kept_limit,
                     const CompactCells& compact, int begin, int end, cv::Mat& differences) {
  const SequenceView kept = reference.coarseCells(stride, compact.geometry());
  const int known_end = std::clamp(std::min(kept.count, kept_limit), begin, end);
  if (known_end > begin) {
    cv::Mat columns = differences.colRange(0, known_end - begin);
    computeDifferenceMatrix(query_cells, kept.slice(begin, known_end), columns);
  }
  if (known_end < end) {
    const DescriptorSequence cells = compact.cells(reference, known_end * stride, stride, end - known_end);
    cv::Mat columns = differences.colRange(known_end - begin, end - begin);
    computeDifferenceMatrix(query_cells, cells.view(), columns);
  }
}

}  // namespace mrs_vpr
