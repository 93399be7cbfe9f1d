#include "mrs_vpr/sampling_level.hpp"

#include <cmath>

namespace mrs_vpr {

SamplingLevel SamplingLevel::make(int stride, const SequenceRows& rows, int reference_count, double velocity_min) {
  SamplingLevel level;
  level.stride = stride;
  level.k_min = -((rows.anchor - rows.first) / stride);
  level.k_max = (rows.last - rows.anchor) / stride;
  level.grid_size = (reference_count - 1) / stride + 1;
  // The slowest velocity reaches least far from the end, so it bounds where trajectories can end.
  level.lowest_end = static_cast<int>(std::lround(velocity_min * -level.k_min));
  level.highest_end = level.grid_size - 1 - static_cast<int>(std::lround(velocity_min * level.k_max));
  return level;
}

}  // namespace mrs_vpr
