#include "mrs_vpr/drive_starts.hpp"

#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace mrs_vpr {
namespace {

std::string refusal(FrameRange test, const std::vector<int>& starts) {
  try {
    refuseTestSequenceAcrossDrives(test, starts);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

TEST(DriveStarts, OnlyATestSequenceWithFramesOfTwoDrivesIsRefused) {
  EXPECT_EQ(refusal({190, 200}, {200}), "");     // the loaded map's last frames
  EXPECT_EQ(refusal({200, 210}, {200}), "");     // the frames added since
  EXPECT_EQ(refusal({190, 210}, {}), "");        // one drive
  EXPECT_EQ(refusal({50, 70}, {20, 200}), "");   // between two junctions
  EXPECT_EQ(refusal({191, 201}, {20, 200}),
            "a test sequence of 10 frames would join the last 9 frames of one drive to the first 1 of the next (a "
            "map was loaded, or a visit appended, between them): their junction is no place; ask about 10 once the "
            "next drive holds that many");
  EXPECT_EQ(refusal({198, 218}, {200}),
            "a test sequence of 20 frames would join the last 2 frames of one drive to the first 18 of the next (a "
            "map was loaded, or a visit appended, between them): their junction is no place; ask about at most 18, "
            "or about 20 once the next drive holds that many");
}

TEST(DriveStarts, AnAcceptedAnswerWhoseTrajectoryCrossesAJunctionIsTakenBack) {
  const SequenceRows centred{0, 19, 10};
  Match match;
  match.reference_index = 205;  // placed at row 10: the trajectory runs from 195 to 214
  match.velocity = 1.0F;
  match.accepted = true;
  EXPECT_EQ(trajectoryFrames(match, centred).begin, 195);
  EXPECT_EQ(trajectoryFrames(match, centred).end, 215);

  Match beside = match;
  refuseAcrossDrives(beside, centred, {195, 215});  // junctions at its ends, not within
  EXPECT_TRUE(beside.accepted);
  EXPECT_FALSE(beside.across_drives);

  refuseAcrossDrives(match, centred, {200});
  EXPECT_FALSE(match.accepted);
  EXPECT_TRUE(match.across_drives);

  Match slower = beside;  // 0.5 frames a test frame: 200 to 209 only
  slower.velocity = 0.5F;
  refuseAcrossDrives(slower, centred, {195, 211});
  EXPECT_TRUE(slower.accepted);

  Match refused_before;  // not accepted for its own reasons: nothing to take back, nothing said
  refused_before.reference_index = 205;
  refused_before.velocity = 1.0F;
  refuseAcrossDrives(refused_before, centred, {200});
  EXPECT_FALSE(refused_before.across_drives);
}

}  // namespace
}  // namespace mrs_vpr
