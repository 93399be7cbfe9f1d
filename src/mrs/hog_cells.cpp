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
  for (int bin = 0; bin < bins_; ++bin) bin_group_.push_back(bin / group_width);
  std::vector<int> members(static_cast<std::size_t>(hog.cellsX() * hog.cellsY() * groups), 0);
  histogram_base_.assign(static_cast<std::size_t>(hog.size() / bins_), 0);
  // Histograms lie in the descriptor in OpenCV's order (HogFrontEnd::offset).
  for (int bx = 0; bx < hog.blocksX(); ++bx) {
    for (int by = 0; by < hog.blocksY(); ++by) {
      for (int cx = 0; cx < 2; ++cx) {
        for (int cy = 0; cy < 2; ++cy) {
          const int base = ((bx + cx) * hog.cellsY() + by + cy) * groups;
          histogram_base_[static_cast<std::size_t>(hog.offset(bx, by, cx, cy) / bins_)] = base;
          for (int bin = 0; bin < bins_; ++bin) ++members[static_cast<std::size_t>(base + bin_group_[static_cast<std::size_t>(bin)])];
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
  for (const int base : histogram_base_) {
    std::uint32_t* group = totals.data() + base;
    for (int bin = 0; bin < bins_; ++bin) group[bin_group_[static_cast<std::size_t>(bin)]] += histogram[bin];
    histogram += bins_;
  }
  const float per_frame = 1.0F / static_cast<float>(frames);
  for (std::size_t k = 0; k < totals.size(); ++k) {
    const float mean = static_cast<float>(totals[k]) * scale_[k] * per_frame;
    cell[k] = static_cast<std::uint8_t>(std::min(255.0F, mean + 0.5F));
  }
}

}  // namespace mrs_vpr
