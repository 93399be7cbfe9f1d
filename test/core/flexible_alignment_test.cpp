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

}  // namespace
}  // namespace mrs_vpr
