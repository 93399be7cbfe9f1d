#pragma once

#include <cstdint>
#include <memory>

#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/parameters.hpp"

namespace mrs_vpr {

/**
 * The compact cells MRS compares below full resolution: a fixed linear map of a front end's
 * descriptor to a much shorter row of bytes, applied to the mean of the s frames ending at a frame
 * (temporal_pooling.hpp). Each front end has its own: patch frequencies for the thumbnail
 * (patch_frequencies.hpp), pooled orientation histograms for HOG (hog_cells.hpp).
 *
 * The maps are linear, so the cell of a mean of frames is the mean of their cells, and fixed, so
 * cells need no fitting to a map, never change as the map grows and mean the same in every map.
 */
class CompactCells {
 public:
  virtual ~CompactCells() = default;

  /// The front end whose descriptors these cells transform.
  const DescriptorParams& geometry() const { return geometry_; }
  /// Bytes of the descriptors transformed.
  int descriptorSize() const { return geometry_.descriptorSize(); }
  /// Bytes per cell.
  virtual int cellSize() const = 0;

  /// The cell of the mean of `frames` descriptors whose byte sums are `sums` (descriptorSize()
  /// values), into `cell` (cellSize() bytes).
  virtual void project(const std::uint16_t* sums, int frames, std::uint8_t* cell) const = 0;

  /// The cell of the `stride` frames of `view` ending at frame `end` (those that exist).
  void cell(SequenceView view, int end, int stride, std::uint8_t* out) const;
  /// Cells ending at first_end, first_end + stride, ... (count of them), as a sequence of cells.
  DescriptorSequence cells(SequenceView view, int first_end, int stride, int count) const;
  /// Throws std::invalid_argument unless `view` holds descriptors of this geometry's size.
  void requireDescriptorsOf(SequenceView view) const;

 protected:
  /// Throws std::invalid_argument when the geometry is invalid.
  explicit CompactCells(const DescriptorParams& geometry);

 private:
  DescriptorParams geometry_;
};

/// The compact cells of the front end `params` chooses. Throws std::invalid_argument when invalid.
std::shared_ptr<const CompactCells> makeCompactCells(const DescriptorParams& params);

/**
 * Differences between `query_cells` and the reference's cells [begin, end) at `stride` (cell i ends
 * at frame i x stride), into `differences` (a column each): the cells the reference's store keeps,
 * below `kept_limit`, are read; the rest (all when it keeps none, or a last, partial one beyond
 * kept_limit) are computed now. Both of MRS's dense passes on compact cells read the map this way.
 */
void cellDifferences(SequenceView query_cells, SequenceView reference, int stride, int kept_limit,
                     const CompactCells& compact, int begin, int end, cv::Mat& differences);

}  // namespace mrs_vpr
