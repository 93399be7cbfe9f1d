#include "mrs_vpr/mrs/hog_cells.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "mrs_vpr/front_end/hog_front_end.hpp"

namespace mrs_vpr {

HogCells::HogCells(const DescriptorParams& geometry)
    : CompactCells(geometry), bins_(geometry.hog_bins) {
  if (!geometry.isHog()) {
    throw std::invalid_argument("pooled orientation histograms are the compact cells of HOG, not of " +
                                geometry.describe());
  }
  const HogFrontEnd hog(geometry);
  const int group_width = (bins_ + kOrientationGroups - 1) / kOrientationGroups;
  const int groups = (bins_ + group_width - 1) / group_width;
  for (int end = group_width; end < bins_ + group_width; end += group_width) group_ends_.push_back(std::min(end, bins_));
  std::vector<int> members(static_cast<std::size_t>(hog.cellsX() * hog.cellsY() * groups), 0);
  histogram_base_.assign(static_cast<std::size_t>(hog.size() / bins_), 0);
  // Histograms lie in the descriptor in OpenCV's order (HogFrontEnd::offset).
  for (int bx = 0; bx < hog.blocksX(); ++bx) {
    for (int by = 0; by < hog.blocksY(); ++by) {
      for (int cx = 0; cx < 2; ++cx) {
        for (int cy = 0; cy < 2; ++cy) {
          const int base = ((bx + cx) * hog.cellsY() + by + cy) * groups;
          histogram_base_[static_cast<std::size_t>(hog.offset(bx, by, cx, cy) / bins_)] = base;
          for (int bin = 0; bin < bins_; ++bin) ++members[static_cast<std::size_t>(base + bin / group_width)];
        }
      }
    }
  }
  for (int count : members) scale_.push_back(1.0F / static_cast<float>(count));
}

void HogCells::project(const std::uint16_t* sums, int frames, std::uint8_t* cell) const {
  // Integer totals: a byte summed over frames and pooled histograms stays far below 2^31.
  thread_local std::vector<std::uint32_t> totals;
  totals.assign(scale_.size(), 0);
  const std::uint16_t* histogram = sums;
  // A histogram's bins are contiguous and so are its groups: each group is a short contiguous sum.
  for (const int base : histogram_base_) {
    std::uint32_t* group = totals.data() + base;
    for (std::size_t g = 0; g < group_ends_.size(); ++g) {
      std::uint32_t total = 0;
      for (int bin = g == 0 ? 0 : group_ends_[g - 1]; bin < group_ends_[g]; ++bin) total += histogram[bin];
      group[g] += total;
    }
    histogram += bins_;
  }
  const float per_frame = 1.0F / static_cast<float>(frames);
  for (std::size_t k = 0; k < totals.size(); ++k) {
    const float mean = static_cast<float>(totals[k]) * scale_[k] * per_frame;
    cell[k] = static_cast<std::uint8_t>(std::min(255.0F, mean + 0.5F));
  }
}

}  // namespace mrs_vpr
