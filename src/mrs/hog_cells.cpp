#include "mrs_vpr/mrs/hog_cells.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "mrs_vpr/front_end/hog_front_end.hpp"
#include "simd/vector_kernel.hpp"

namespace mrs_vpr {
namespace {

/// cell[k] = totals[k] x scale[k] x per_frame, rounded, at most 255.
MRS_VPR_VECTOR_KERNEL
void meansOfTotals(const std::uint32_t* __restrict totals, const float* __restrict scale, int count, float per_frame,
                   std::uint8_t* __restrict cell) {
  for (int k = 0; k < count; ++k) {
    const float mean = static_cast<float>(totals[k]) * scale[k] * per_frame;
    cell[k] = static_cast<std::uint8_t>(std::min(255.0F, mean + 0.5F));
  }
}

}  // namespace

HogCells::HogCells(const DescriptorParams& geometry)
    : CompactCells(geometry) {
  if (!geometry.isHog()) {
    throw std::invalid_argument("pooled orientation histograms are the compact cells of HOG, not of " +
                                geometry.describe());
  }
  const HogFrontEnd hog(geometry);
  bins_ = geometry.hog_bins;
  group_width_ = (bins_ + kOrientationGroups - 1) / kOrientationGroups;
  const int groups = (bins_ + group_width_ - 1) / group_width_;
  std::vector<int> members(static_cast<std::size_t>(hog.cellsX() * hog.cellsY() * groups), 0);
  // Histograms lie in the descriptor in OpenCV's order (HogFrontEnd::offset).
  for (int bx = 0; bx < hog.blocksX(); ++bx) {
    for (int by = 0; by < hog.blocksY(); ++by) {
      for (int cx = 0; cx < 2; ++cx) {
        for (int cy = 0; cy < 2; ++cy) {
          const Histogram histogram{hog.offset(bx, by, cx, cy), ((bx + cx) * hog.cellsY() + by + cy) * groups};
          histograms_.push_back(histogram);
          for (int bin = 0; bin < bins_; ++bin) {
            ++members[static_cast<std::size_t>(histogram.first_cell_byte + bin / group_width_)];
          }
        }
      }
    }
  }
  for (int count : members) scale_.push_back(1.0F / static_cast<float>(count));
}

void HogCells::project(const std::uint16_t* sums, int frames, std::uint8_t* cell) const {
  // Integer totals (so their order does not matter): a byte summed over frames and pooled histograms
  // stays far below 2^31. On the stack for the usual geometries, which keeps a cell free of allocations.
  constexpr std::size_t kStackBytes = 256;
  std::array<std::uint32_t, kStackBytes> stack_totals;  // Only the cell's bytes are zeroed.
  std::vector<std::uint32_t> heap_totals;
  std::uint32_t* totals = stack_totals.data();
  if (scale_.size() > kStackBytes) {
    heap_totals.resize(scale_.size());
    totals = heap_totals.data();
  }
  std::fill(totals, totals + scale_.size(), 0U);
  // The query's cells are computed anew for every query: the default 9 bins in groups of 3 are written
  // out, which makes a cell about three times cheaper than the loops over groups and bins below.
  if (bins_ == 9 && group_width_ == 3) {
    for (const Histogram& histogram : histograms_) {
      const std::uint16_t* bin = sums + histogram.first_byte;
      std::uint32_t* total = totals + histogram.first_cell_byte;
      total[0] += static_cast<std::uint32_t>(bin[0] + bin[1] + bin[2]);
      total[1] += static_cast<std::uint32_t>(bin[3] + bin[4] + bin[5]);
      total[2] += static_cast<std::uint32_t>(bin[6] + bin[7] + bin[8]);
    }
  } else {
    for (const Histogram& histogram : histograms_) {
      for (int bin = 0; bin < bins_; ++bin) {
        totals[histogram.first_cell_byte + bin / group_width_] += sums[histogram.first_byte + bin];
      }
    }
  }
  meansOfTotals(totals, scale_.data(), static_cast<int>(scale_.size()), 1.0F / static_cast<float>(frames), cell);
}

}  // namespace mrs_vpr
