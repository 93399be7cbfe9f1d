#pragma once

#include <cstdint>
#include <vector>

#include "mrs_vpr/mrs/compact_cells.hpp"

namespace mrs_vpr {

/**
 * The compact cells of the HOG front end: for every HOG cell, its orientation histogram in
 * kOrientationGroups groups of neighbouring bins, one byte each, the mean of that cell's bins over
 * every block that holds it. A 128 x 64 window with cells of 16 px (8 x 4 cells) and 9 bins gives
 * 96-byte cells, 1/8 of the descriptor, as the thumbnail's patch frequencies give 96 bytes for its
 * 8 x 4 patches.
 *
 * Chosen on the tune half of the real benchmark (M = 9137, N = 300 at stride 4 and N = 200 at
 * stride 2): the coarse table of these cells put the true place first among its distinct minima in
 * every query, as did 2 x 2 cells with all 9 bins (72 bytes), 2 x 1 cells in 3 groups (48 bytes) and
 * each cell's whole gradient energy (32 bytes); these cells accepted as many answers as any (doc/front_ends.md).
 */
class HogCells : public CompactCells {
 public:
  /// Groups of neighbouring orientation bins per HOG cell.
  static constexpr int kOrientationGroups = 3;

  /// Cells of HOG descriptors of `geometry`. Throws std::invalid_argument when it is invalid or not HOG's.
  explicit HogCells(const DescriptorParams& geometry);

  int cellSize() const override { return static_cast<int>(scale_.size()); }
  void project(const std::uint16_t* sums, int frames, std::uint8_t* cell) const override;

 private:
  /// One HOG cell's histogram in one block: where its bins lie in the descriptor, and the first of the
  /// cell bytes its groups of bins are pooled into.
  struct Histogram {
    int first_byte = 0;
    int first_cell_byte = 0;
  };
  std::vector<Histogram> histograms_;
  int bins_ = 0;
  int group_width_ = 0;  ///< Neighbouring bins per group (the last group may have fewer).
  std::vector<float> scale_;  ///< Per cell byte: 1 / the descriptor bytes pooled into it.
};

}  // namespace mrs_vpr
