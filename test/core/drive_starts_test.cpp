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

TEST(DriveStarts, AStartIsInsertedInOrderOnceAndFrameZeroIsNone) {
  std::vector<int> starts;
  EXPECT_TRUE(insertDriveStart(starts, 120));
  EXPECT_TRUE(insertDriveStart(starts, 40));
  EXPECT_FALSE(insertDriveStart(starts, 120));
  EXPECT_FALSE(insertDriveStart(starts, 0));
  EXPECT_EQ(starts, (std::vector<int>{40, 120}));
  EXPECT_THROW(insertDriveStart(starts, -1), std::invalid_argument);
  EXPECT_EQ(starts, (std::vector<int>{40, 120}));
}

TEST(DriveStarts, OnlyATestSequenceWithFramesOfTwoDrivesIsRefused) {
  EXPECT_EQ(refusal({190, 200}, {200}), "");      // the loaded map's last frames
  EXPECT_EQ(refusal({200, 210}, {200}), "");      // the frames added since
  EXPECT_EQ(refusal({190, 210}, {}), "");         // one drive
  EXPECT_EQ(refusal({50, 70}, {20, 200}), "");    // between two junctions
  EXPECT_EQ(refusal({190, 200}, {20, 200}), "");  // ending where a drive starts
  EXPECT_EQ(refusal({191, 201}, {20, 200}),
            "a test sequence of map frames [191, 201) runs across the start of a drive at frame 200 (a map was "
            "loaded, as by a node started on its database or ~load_map, or a visit appended, before it): the "
            "junction of two drives is no place; ask about 10 once the drive holds that many");
  EXPECT_EQ(refusal({198, 218}, {200}),
            "a test sequence of map frames [198, 218) runs across the start of a drive at frame 200 (a map was "
            "loaded, as by a node started on its database or ~load_map, or a visit appended, before it): the "
            "junction of two drives is no place; ask about at most 18 frames, or about 20 once the drive holds that "
            "many");
  EXPECT_EQ(refusal({190, 230}, {195, 220}),  // the advice counts from the last junction
            "a test sequence of map frames [190, 230) runs across the start of a drive at frame 220 (a map was "
            "loaded, as by a node started on its database or ~load_map, or a visit appended, before it): the "
            "junction of two drives is no place; ask about at most 10 frames, or about 40 once the drive holds that "
            "many");
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

  // The path is placed at the searched velocity, a double: 1.3 x 45 rounds to 59 frames, the float
  // 1.3F that the answer holds x 45 to 58.
  Match long_fast;
  long_fast.reference_index = 1000;
  long_fast.velocity = 1.3F;
  const SequenceRows long_centred{0, 90, 45};
  EXPECT_EQ(trajectoryFrames(long_fast, long_centred, {1.2, 1.3}).begin, 1000 - 59);
  EXPECT_EQ(trajectoryFrames(long_fast, long_centred, {1.2, 1.3}).end, 1000 + 59 + 1);

  Match refused_before;  // not accepted for its own reasons: nothing to take back, nothing said
  refused_before.reference_index = 205;
  refused_before.velocity = 1.0F;
  refuseAcrossDrives(refused_before, centred, {200});
  EXPECT_FALSE(refused_before.across_drives);
}

}  // namespace
}  // namespace mrs_vpr
