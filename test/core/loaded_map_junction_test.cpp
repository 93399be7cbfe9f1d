#include "mrs_vpr/loaded_map_junction.hpp"

#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

namespace mrs_vpr {
namespace {

std::string refusal(long long first, long long end, long long loaded_frames) {
  try {
    refuseSequenceAcrossLoadedMap(first, end, loaded_frames);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

TEST(LoadedMapJunction, OnlyASequenceWithFramesOnBothSidesIsRefused) {
  EXPECT_EQ(refusal(190, 200, 200), "");  // the loaded map's last frames
  EXPECT_EQ(refusal(200, 210, 200), "");  // the frames added since
  EXPECT_EQ(refusal(190, 210, 0), "");    // no map loaded: one drive
  EXPECT_EQ(refusal(-5, 5, 200), "");     // beyond the map: the caller's own message
  EXPECT_EQ(refusal(191, 201, 200),
            "a test sequence of 10 frames would join the loaded map's last 9 frames to the 1 added since: two "
            "drives, whose junction is no place; ask again once 10 frames have been added");
  EXPECT_EQ(refusal(198, 218, 200),
            "a test sequence of 20 frames would join the loaded map's last 2 frames to the 18 added since: two "
            "drives, whose junction is no place; ask again once 20 frames have been added, or about at most 18 now");
}

}  // namespace
}  // namespace mrs_vpr
