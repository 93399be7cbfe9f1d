#include "mrs_vpr/temporal_pooling.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

namespace mrs_vpr {

void poolCell(SequenceView view, int end, int stride, int pixel_pooling, std::uint8_t* out) {
  const int size = view.descriptor_size;
  if (pixel_pooling < 1 || size % pixel_pooling != 0) {
    throw std::invalid_argument("pixel pooling " + std::to_string(pixel_pooling) +
                                " does not divide the descriptor size " + std::to_string(size));
  }
  const int begin = std::max(0, end - stride + 1);
  end = std::min(end, view.count - 1);  // A cell may end past the view: pool the frames that exist.
  const int frames = end - begin + 1;
  if (frames == 1 && pixel_pooling == 1) {
    std::copy(view.frame(end), view.frame(end) + size, out);
    return;
  }
  // uint16 sums hold up to 257 frames of uint8; plain loops over restrict pointers vectorise.
  thread_local std::vector<std::uint16_t> sums;
  sums.assign(static_cast<std::size_t>(size), 0);
  std::uint16_t* __restrict sum = sums.data();
  for (int f = begin; f <= end; ++f) {
    const std::uint8_t* __restrict frame = view.frame(f);
    for (int i = 0; i < size; ++i) sum[i] = static_cast<std::uint16_t>(sum[i] + frame[i]);
  }
  // Multiplying by the reciprocal vectorises; dividing would not.
  const float scale = 1.0F / static_cast<float>(frames * pixel_pooling);
  for (int o = 0; o < size / pixel_pooling; ++o) {
    std::uint32_t total = 0;
    for (int p = 0; p < pixel_pooling; ++p) total += sum[o * pixel_pooling + p];
    out[o] = static_cast<std::uint8_t>(static_cast<float>(total) * scale + 0.5F);
  }
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

}  // namespace mrs_vpr
