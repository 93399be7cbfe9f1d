#include <gtest/gtest.h>

#include <vector>

#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/flexible_alignment.hpp"
#include "mrs_vpr/trajectory_search.hpp"
#include "support/route_fixture.hpp"

namespace mrs_vpr {
namespace {

using testing_support::standardRoute;

/// A test traversal made of the map's own frames `frames`, in that order.
DescriptorSequence traversalOf(const DescriptorSequence& map, const std::vector<int>& frames) {
  DescriptorSequence traversal(map.descriptorSize());
  for (int frame : frames) traversal.append(map.descriptorRow(frame));
  return traversal;
}

/// Frames 100..129 of the map at its own speed, a stop of 6 frames at 130, then 131..140.
std::vector<int> driveWithAStop() {
  std::vector<int> frames;
  for (int frame = 100; frame <= 129; ++frame) frames.push_back(frame);
  for (int repeat = 0; repeat < 6; ++repeat) frames.push_back(130);
  for (int frame = 131; frame <= 140; ++frame) frames.push_back(frame);
  return frames;
}

TEST(FlexibleAlignment, MovesAStraightAnswerThatAStopLeftBehindToTheTrueEnd) {
  const DescriptorSequence& map = standardRoute().reference;
  const DescriptorSequence query = traversalOf(map, driveWithAStop());
  const SequenceRows rows = wholeSequenceRows(query.size(), WindowAlignment::kCausal);
  // The straight trajectory at the map's speed through the first 30 frames ends 6 frames short.
  const int straight_end = 134;
  EXPECT_EQ(realignEnd(map.view(), query.view(), rows, straight_end, 1.0, 8, 10), 140);
  EXPECT_EQ(realignEnd(map.view(), query.view(), rows, straight_end, 1.0, 0, 10), straight_end);
}

TEST(FlexibleAlignment, KeepsAnAnswerThatIsAlreadyRightAndOneNearTheMapsEdge) {
  const DescriptorSequence& map = standardRoute().reference;
  std::vector<int> frames;
  for (int frame = 200; frame < 240; ++frame) frames.push_back(frame);
  const DescriptorSequence query = traversalOf(map, frames);
  const SequenceRows rows = wholeSequenceRows(query.size(), WindowAlignment::kCausal);
  EXPECT_EQ(realignEnd(map.view(), query.view(), rows, 239, 1.0, 8, 10), 239);
  // A band that would leave the map keeps the straight answer.
  EXPECT_EQ(realignEnd(map.view(), query.view(), rows, 42, 1.0, 8, 10), 42);
}

TEST(FlexibleAlignment, ACentredAnswerWhoseMiddleFrameIsInAStopIsTheStopsFrame) {
  // Frames 100..116, a stop of 6 frames at 117 (rows 17..22), then 118..134: 40 rows, the middle one
  // (row 20) in the stop, where the path stays in one column.
  const DescriptorSequence& map = standardRoute().reference;
  std::vector<int> frames;
  for (int frame = 100; frame <= 116; ++frame) frames.push_back(frame);
  for (int repeat = 0; repeat < 6; ++repeat) frames.push_back(117);
  for (int frame = 118; frame <= 134; ++frame) frames.push_back(frame);
  const DescriptorSequence query = traversalOf(map, frames);
  const SequenceRows rows = wholeSequenceRows(query.size(), WindowAlignment::kCentred);
  ASSERT_EQ(frames[static_cast<std::size_t>(rows.anchor)], 117);
  // The straight trajectory at the map's speed puts the middle row at 117 + 3, half the stop ahead.
  EXPECT_EQ(realignEnd(map.view(), query.view(), rows, 120, 1.0, 8, 10), 117);
  EXPECT_EQ(realignEnd(map.view(), query.view(), rows, 117, 1.0, 8, 10), 117);
}


TEST(FlexibleAlignment, AStopAsLongInTheMapAsInTheQueryIsWalkedInStep) {
  // The map stood at frame 108 for eight frames (108..115 show one view), and so did the test traversal.
  // Nothing in the differences tells the frames of the stop apart: one map frame per test frame, the free
  // step, puts the middle row (the stop's fifth frame) on the map's fifth frame of it.
  const DescriptorSequence& route = standardRoute().reference;
  std::vector<int> map_frames;
  for (int frame = 0; frame < 300; ++frame) map_frames.push_back(frame >= 108 && frame <= 115 ? 108 : frame);
  const DescriptorSequence map = traversalOf(route, map_frames);
  std::vector<int> query_frames;
  for (int frame = 92; frame < 132; ++frame) query_frames.push_back(frame);
  const DescriptorSequence query = traversalOf(map, query_frames);
  const SequenceRows rows = wholeSequenceRows(query.size(), WindowAlignment::kCentred);
  ASSERT_EQ(query_frames[static_cast<std::size_t>(rows.anchor)], 112);
  EXPECT_EQ(realignEnd(map.view(), query.view(), rows, 112, 1.0, 8, 10), 112);
}

}  // namespace
}  // namespace mrs_vpr
