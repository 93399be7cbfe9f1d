#include "mrs_vpr/mrs/sampling_level.hpp"

#include <cmath>

namespace mrs_vpr {

SamplingLevel SamplingLevel::make(int stride, const SequenceRows& rows, int reference_count, double velocity_min) {
  SamplingLevel level;
  level.stride = stride;
  level.k_min = -((rows.anchor - rows.first) / stride);
  level.k_max = (rows.last - rows.anchor) / stride;
  // Cells end at frames J * stride; the last one may end past the reference and then pools only
  // the frames that exist. Without it the newest stride - 1 frames would be no coarse cell's end,
  // and a sequence ending there would be found only by a neighbour's weak, phase-shifted match.
  level.grid_size = (reference_count + stride - 2) / stride + 1;
  // The slowest velocity reaches least far from the end, so it bounds where trajectories can end.
  level.lowest_end = static_cast<int>(std::lround(velocity_min * -level.k_min));
  level.highest_end = level.grid_size - 1 - static_cast<int>(std::lround(velocity_min * level.k_max));
  return level;
}

}  // namespace mrs_vpr
