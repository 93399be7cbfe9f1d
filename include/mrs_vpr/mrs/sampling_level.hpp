#pragma once

#include "mrs_vpr/trajectory_search.hpp"

namespace mrs_vpr {

/**
 * One level of the coarse-to-fine search, of stride s: the test cells ending at frames
 * `anchor + k * s` (k in [k_min, k_max]; row k - k_min of the level's difference matrix) against the
 * reference grid of cells ending at frames J * s (the last one possibly past the reference's newest
 * frame, pooling only the frames that exist). Particle indices are grid indices J.
 */
struct SamplingLevel {
  int stride = 1;
  int k_min = 0;
  int k_max = 0;
  int grid_size = 0;
  int lowest_end = 0;   ///< Lowest end whose trajectory fits in the grid at the slowest velocity.
  int highest_end = 0;  ///< Highest such end.

  /// The level of `stride` for a test sequence's rows and a reference of `reference_count` frames.
  static SamplingLevel make(int stride, const SequenceRows& rows, int reference_count, double velocity_min);

  int rows() const { return k_max - k_min + 1; }
  /// The level's rows as a sequence: anchored at k = 0.
  SequenceRows sequenceRows() const { return {0, rows() - 1, -k_min}; }
  bool empty() const { return lowest_end > highest_end; }
};

}  // namespace mrs_vpr
