#include <gtest/gtest.h>

#include "mrs_vpr/mrs/sampling_level.hpp"

namespace mrs_vpr {
namespace {

TEST(SamplingLevel, MakeComputesRowsGridAndFeasibleEnds) {
  // Causal sequence of 100 frames, stride 4, reference of 600 frames, slowest velocity 0.8.
  const SamplingLevel level = SamplingLevel::make(4, SequenceRows{0, 99, 99}, 600, 0.8);
  EXPECT_EQ(level.k_min, -24);
  EXPECT_EQ(level.k_max, 0);
  EXPECT_EQ(level.rows(), 25);
  // Cells end at 0, 4, ..., 600: the last one past the newest frame 599, so that frames 597..599
  // still end a cell.
  EXPECT_EQ(level.grid_size, 151);
  EXPECT_EQ(level.lowest_end, 19);  // round(0.8 * 24)
  EXPECT_EQ(level.highest_end, 150);
  EXPECT_EQ(SamplingLevel::make(4, SequenceRows{0, 99, 99}, 601, 0.8).grid_size, 151);  // 600 is a frame.
  EXPECT_FALSE(level.empty());
  const SequenceRows rows = level.sequenceRows();
  EXPECT_EQ(rows.first, 0);
  EXPECT_EQ(rows.last, 24);
  EXPECT_EQ(rows.anchor, 24);
  // A reference too short for the sequence has no feasible end.
  EXPECT_TRUE(SamplingLevel::make(1, SequenceRows{0, 99, 99}, 50, 0.8).empty());
}

}  // namespace
}  // namespace mrs_vpr
