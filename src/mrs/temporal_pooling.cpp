#include "mrs_vpr/mrs/temporal_pooling.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace mrs_vpr {
namespace {

/// out[o] = the sum of run o of kRun consecutive values. A compile-time run length lets the loop
/// vectorise.
template <int kRun, typename In, typename Out>
void foldRunsOf(const In* __restrict in, Out* __restrict out, int runs) {
  for (int o = 0; o < runs; ++o) {
    Out total = 0;
    for (int p = 0; p < kRun; ++p) total = static_cast<Out>(total + in[o * kRun + p]);
    out[o] = total;
  }
}

/// out[o] = the sum of run o of `run` consecutive values; the common run lengths are compiled.
template <typename In, typename Out>
void foldRuns(const In* in, Out* out, int runs, int run) {
  switch (run) {
    case 1: foldRunsOf<1>(in, out, runs); return;
    case 2: foldRunsOf<2>(in, out, runs); return;
    case 4: foldRunsOf<4>(in, out, runs); return;
    case 8: foldRunsOf<8>(in, out, runs); return;
    default:
      for (int o = 0; o < runs; ++o) {
        Out total = 0;
        for (int p = 0; p < run; ++p) total = static_cast<Out>(total + in[o * run + p]);
        out[o] = total;
      }
  }
}

/// The rounded means of `samples` values from their totals. Multiplying by the reciprocal
/// vectorises where dividing would not. Every pooling path rounds here, so that cells pooled from
/// a map and from a test sequence are equal to the bit.
void meanOfTotals(const std::uint32_t* __restrict totals, int count, int samples, std::uint8_t* __restrict out) {
  const float scale = 1.0F / static_cast<float>(samples);
  for (int o = 0; o < count; ++o) out[o] = static_cast<std::uint8_t>(static_cast<float>(totals[o]) * scale + 0.5F);
}

/// The first and last frame of the cell ending at `end` over `stride` frames of a view of `count`
/// frames. A cell may end past the view: it pools the frames that exist.
std::pair<int, int> cellFrames(int end, int stride, int count) {
  return {std::max(0, end - stride + 1), std::min(end, count - 1)};
}

}  // namespace

void requirePixelPoolingDivides(int pixel_pooling, int descriptor_size, const std::string& name) {
  if (pixel_pooling < 1 || descriptor_size % pixel_pooling != 0) {
    throw std::invalid_argument(name + " " + std::to_string(pixel_pooling) + " does not divide the descriptor size " +
                                std::to_string(descriptor_size));
  }
}

void poolCell(SequenceView view, int end, int stride, int pixel_pooling, std::uint8_t* out) {
  const int size = view.descriptor_size;
  requirePixelPoolingDivides(pixel_pooling, size);
  const auto [first, last] = cellFrames(end, stride, view.count);
  if (first == last && pixel_pooling == 1) {
    std::copy(view.frame(last), view.frame(last) + size, out);
    return;
  }
  // uint16 sums hold up to 257 frames of uint8; plain loops over restrict pointers vectorise.
  thread_local std::vector<std::uint16_t> sums;
  sums.assign(static_cast<std::size_t>(size), 0);
  std::uint16_t* __restrict sum = sums.data();
  for (int f = first; f <= last; ++f) {
    const std::uint8_t* __restrict frame = view.frame(f);
    for (int i = 0; i < size; ++i) sum[i] = static_cast<std::uint16_t>(sum[i] + frame[i]);
  }
  const int cells = size / pixel_pooling;
  thread_local std::vector<std::uint32_t> totals;
  totals.resize(static_cast<std::size_t>(cells));
  foldRuns(sum, totals.data(), cells, pixel_pooling);
  meanOfTotals(totals.data(), cells, (last - first + 1) * pixel_pooling, out);
}

DescriptorSequence poolSequence(SequenceView view, int first_end, int stride, int count, int pixel_pooling) {
  DescriptorSequence pooled(view.descriptor_size / pixel_pooling);
  pooled.reserve(count);
  cv::Mat cell(1, view.descriptor_size / pixel_pooling, CV_8U);
  for (int i = 0; i < count; ++i) {
    poolCell(view, first_end + i * stride, stride, pixel_pooling, cell.data);
    pooled.append(cell);
  }
  return pooled;
}

PooledReference::PooledReference(SequenceView reference, int stride, int pixel_pooling)
    : reference_(reference), kept_(reference.pooledCells(stride, pixel_pooling)), stride_(stride),
      pixel_pooling_(pixel_pooling) {}

const std::uint8_t* PooledReference::cell(int grid_index) {
  if (stride_ == 1 && pixel_pooling_ == 1) return reference_.frame(grid_index);
  if (kept_.count > 0) return kept_.frame(grid_index);
  auto [it, inserted] = cells_.try_emplace(grid_index);
  if (inserted) {
    it->second.resize(static_cast<std::size_t>(cellSize()));
    poolCell(reference_, grid_index * stride_, stride_, pixel_pooling_, it->second.data());
  }
  return it->second.data();
}

PixelRunSums::PixelRunSums(SequenceView view, int pixel_pooling)
    : frames_(view.count), pixel_pooling_(pixel_pooling) {
  requirePixelPoolingDivides(pixel_pooling, view.descriptor_size);
  cell_size_ = view.descriptor_size / pixel_pooling;
  // uint16 holds the sum of up to 257 uint8 pixels; pixel pooling is at most 64.
  sums_.resize(static_cast<std::size_t>(frames_) * static_cast<std::size_t>(cell_size_));
  for (int f = 0; f < frames_; ++f) foldRuns(view.frame(f), frameSums(f), cell_size_, pixel_pooling);
}

DescriptorSequence PixelRunSums::pool(int first_end, int stride, int count) const {
  DescriptorSequence pooled(cell_size_);
  pooled.reserve(count);
  cv::Mat cell(1, cell_size_, CV_8U);
  std::vector<std::uint32_t> totals(static_cast<std::size_t>(cell_size_));
  for (int i = 0; i < count; ++i) {
    const auto [first, last] = cellFrames(first_end + i * stride, stride, frames_);
    std::fill(totals.begin(), totals.end(), 0U);
    std::uint32_t* __restrict total = totals.data();
    for (int f = first; f <= last; ++f) {
      const std::uint16_t* __restrict sum = frameSums(f);
      for (int o = 0; o < cell_size_; ++o) total[o] += sum[o];
    }
    meanOfTotals(total, cell_size_, (last - first + 1) * pixel_pooling_, cell.data);
    pooled.append(cell);
  }
  return pooled;
}

}  // namespace mrs_vpr
