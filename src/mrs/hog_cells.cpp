#include "mrs_vpr/mrs/hog_cells.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "mrs_vpr/front_end/hog_front_end.hpp"

namespace mrs_vpr {

HogCells::HogCells(const DescriptorParams& geometry)
    : CompactCells(geometry) {
  if (!geometry.isHog()) {
    throw std::invalid_argument("pooled orientation histograms are the compact cells of HOG, not of " +
                                geometry.describe());
  }
  const HogFrontEnd hog(geometry);
  const int bins = geometry.hog_bins;
  const int group_width = (bins + kOrientationGroups - 1) / kOrientationGroups;
  const int groups = (bins + group_width - 1) / group_width;
  std::vector<int> members(static_cast<std::size_t>(hog.cellsX() * hog.cellsY() * groups), 0);
  target_.assign(static_cast<std::size_t>(hog.size()), 0);
  // Histograms lie in the descriptor in OpenCV's order (HogFrontEnd::offset).
  for (int bx = 0; bx < hog.blocksX(); ++bx) {
    for (int by = 0; by < hog.blocksY(); ++by) {
      for (int cx = 0; cx < 2; ++cx) {
        for (int cy = 0; cy < 2; ++cy) {
          const int base = ((bx + cx) * hog.cellsY() + by + cy) * groups;
          const int first_byte = hog.offset(bx, by, cx, cy);
          for (int bin = 0; bin < bins; ++bin) {
            const int cell_byte = base + bin / group_width;
            target_[static_cast<std::size_t>(first_byte + bin)] = cell_byte;
            ++members[static_cast<std::size_t>(cell_byte)];
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
  std::array<std::uint32_t, kStackBytes> stack_totals{};
  std::vector<std::uint32_t> heap_totals;
  std::uint32_t* totals = stack_totals.data();
  if (scale_.size() > kStackBytes) {
    heap_totals.assign(scale_.size(), 0);
    totals = heap_totals.data();
  }
  // A group's bins are neighbours: sum each run of bytes with one target in a register, so that
  // consecutive adds do not wait on each other's store to the same total.
  const std::size_t size = target_.size();
  std::uint32_t run = 0;
  for (std::size_t i = 0; i < size; ++i) {
    run += sums[i];
    if (i + 1 == size || target_[i + 1] != target_[i]) {
      totals[target_[i]] += run;
      run = 0;
    }
  }
  const float per_frame = 1.0F / static_cast<float>(frames);
  for (std::size_t k = 0; k < scale_.size(); ++k) {
    const float mean = static_cast<float>(totals[k]) * scale_[k] * per_frame;
    cell[k] = static_cast<std::uint8_t>(std::min(255.0F, mean + 0.5F));
  }
}

}  // namespace mrs_vpr
