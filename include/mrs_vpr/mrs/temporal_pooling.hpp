#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/mrs/compact_cells.hpp"

namespace mrs_vpr {

/**
 * Pooling, the low-pass filter of the coarse-to-fine search. A level of stride s > 1 compares
 * "cells": the compact cells (compact_cells.hpp) of the mean descriptor of the s frames
 * ending at a frame (frames end - s + 1 .. end, clipped to the frames that exist).
 *
 * Subsampling alone (every s-th frame, as the paper writes) only works when s consecutive frames
 * look alike; on keyframed or fast imagery a coarse test frame meets a reference frame up to s/2
 * frames from its place and the coarse level sees nothing (measured on Nordland, N = 100 with two
 * levels: 57% success subsampled, 95.5% pooled). The mean of s frames still overlaps the mean of the
 * matching s frames when the alignment is off by a few frames. Cells only look back, so a cell
 * never changes once its last frame exists.
 *
 * The cells ending at grid index J * stride of a reference: the frames themselves at stride 1, the
 * store's kept cells when it has them, else computed on first use and remembered.
 */
class PooledReference {
 public:
  PooledReference(SequenceView reference, int stride, const CompactCells& compact);

  int stride() const { return stride_; }
  /// Bytes per cell.
  int cellSize() const { return stride_ == 1 ? reference_.descriptor_size : compact_.cellSize(); }
  /// Cells J = 0 .. size() - 1: SamplingLevel's grid, whose last cell may end past the newest frame
  /// (it pools the frames that exist), so that every cell a search of that level asks for is here.
  int size() const { return (reference_.count + stride_ - 2) / stride_ + 1; }
  const std::uint8_t* cell(int grid_index);

  /// Cells first .. first + count - 1, `pitch` bytes apart.
  struct Run {
    const std::uint8_t* cells = nullptr;
    std::ptrdiff_t pitch = 0;
    int count = 0;
  };
  /// The longest run of consecutive cells from `first` (at most `wanted` of them, computed where
  /// missing) that lie one pitch apart, so that they can be compared in one sweep.
  Run run(int first, int wanted);

 private:
  SequenceView reference_;
  SequenceView kept_;
  int stride_;
  const CompactCells& compact_;
  std::vector<std::uint8_t> cells_;  ///< Cells computed here, size() x cellSize() once used.
  std::vector<char> known_;          ///< Which of cells_ are computed.
};

}  // namespace mrs_vpr
