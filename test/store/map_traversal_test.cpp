// The traversal a map records (MapTraversal): written, read back, forgotten when the frames change,
// ignored when damaged or stale, and compared with the keyframing of the frames asked about.

#include <gtest/gtest.h>
#include <sqlite3.h>

#include <cstdint>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "mrs_vpr/store/map_database.hpp"
#include "mrs_vpr/store/map_traversal.hpp"
#include "support/front_ends.hpp"
#include "support/temporary_folder.hpp"

namespace mrs_vpr {
namespace {

using testing_support::thumbnailParams;

class MapTraversalTest : public ::testing::Test {
 protected:
  std::string path(const std::string& name) const { return folder_.path(name); }

  static std::vector<StoredFrame> frames(int count) {
    std::vector<StoredFrame> result;
    for (int i = 0; i < count; ++i) {
      result.push_back({cv::Mat(1, thumbnailParams().descriptorSize(), CV_8UC1, cv::Scalar(i)),
                        Stamp::fromSecondsAndNanoseconds(static_cast<std::uint32_t>(i + 1), 0), "", i});
    }
    return result;
  }

  /// A map of 5 keyframes of a traversal of 8 frames kept at an appearance change of 0.4.
  std::string recordedMap(const std::string& name) const {
    MapDatabase map(path(name), thumbnailParams());
    map.append(frames(5));
    MapTraversal traversal;
    traversal.frames = 8;
    traversal.min_appearance_change = 0.4;
    map.setTraversal(traversal);
    return path(name);
  }

 private:
  testing_support::TemporaryFolder folder_{"mrs_vpr_map_traversal_test"};
};

TEST_F(MapTraversalTest, IsReadBackAsWritten) {
  const MapDatabase map(recordedMap("map.db"), MapAccess::kReadOnly);
  ASSERT_TRUE(map.traversal().has_value());
  EXPECT_EQ(map.traversal()->frames, 8);
  EXPECT_EQ(map.traversal()->min_appearance_change, 0.4);
}

TEST_F(MapTraversalTest, IsForgottenWhenTheFramesChange) {
  // Appended to (by the node, say), replaced or emptied, the map's frames are no longer its alone.
  for (const std::string& change : {"append", "replace", "clear"}) {
    SCOPED_TRACE(change);
    const std::string file = recordedMap(change + ".db");
    {
      MapDatabase map(file, thumbnailParams());
      if (change == "append") map.append(frames(1));
      if (change == "replace") map.replace([](const auto& insert) { insert(frames(1).front()); });
      if (change == "clear") map.clear();
      EXPECT_FALSE(map.traversal().has_value());
    }
    EXPECT_FALSE(MapDatabase(file, MapAccess::kReadOnly).traversal().has_value());
  }
}

TEST_F(MapTraversalTest, ReplacedFramesRecordTheirOwnTraversalAndAFailedReplaceKeepsTheOld) {
  const std::string file = recordedMap("replaced.db");
  {
    MapDatabase map(file, thumbnailParams());
    // A failed replace (a frame of another size) rolls back, the record with it.
    const auto bad = [](const auto& insert) {
      insert(frames(1).front());
      insert(StoredFrame{cv::Mat(1, 3, CV_8UC1, cv::Scalar(0)), Stamp::fromSecondsAndNanoseconds(9, 0), "", 9});
    };
    MapTraversal other;
    other.frames = 3;
    EXPECT_THROW(map.replace(bad, other), std::invalid_argument);
  }
  ASSERT_TRUE(MapDatabase(file, MapAccess::kReadOnly).traversal().has_value());
  EXPECT_EQ(MapDatabase(file, MapAccess::kReadOnly).traversal()->frames, 8);
  {
    MapDatabase map(file, thumbnailParams());
    MapTraversal replaced;
    replaced.frames = 12;
    replaced.min_appearance_change = 0.25;
    map.replace([](const auto& insert) {
      for (const StoredFrame& frame : frames(3)) insert(frame);
    }, replaced);
    ASSERT_TRUE(map.traversal().has_value());
    EXPECT_EQ(map.traversal()->frames, 12);
  }
  const MapDatabase read(file, MapAccess::kReadOnly);
  ASSERT_TRUE(read.traversal().has_value());
  EXPECT_EQ(read.traversal()->frames, 12);
  EXPECT_EQ(read.traversal()->min_appearance_change, 0.25);
}

TEST_F(MapTraversalTest, ReadAgainTheRecordIsThatOfTheFramesAsTheyAreNow) {
  // A map opened, then extended by another program: the record read at the open no longer holds.
  const std::string file = recordedMap("read_again.db");
  const MapDatabase opened(file, MapAccess::kReadOnly);
  ASSERT_TRUE(opened.readTraversal().has_value());
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(file.c_str(), &db), SQLITE_OK);
  EXPECT_EQ(sqlite3_exec(db, "INSERT INTO frames SELECT id + 100, stamp_ns + 100, frame_id, sequence, descriptor "
                             "FROM frames WHERE id = 1",
                         nullptr, nullptr, nullptr),
            SQLITE_OK);
  sqlite3_close(db);
  EXPECT_TRUE(opened.traversal().has_value());  // As it was at the open.
  EXPECT_FALSE(opened.readTraversal().has_value());
}

TEST_F(MapTraversalTest, ADamagedOrStaleRecordIsNoneAndTheMapStillOpens) {
  // A hint for evaluating the map, never a reason to refuse it. Stale: frames that another program
  // (an older release of this package, sqlite3) added without forgetting the record.
  for (const std::string& change :
       {"UPDATE metadata SET value = 'many' WHERE key = 'traversal_frames'",
        "UPDATE metadata SET value = '8.5' WHERE key = 'traversal_frames'",
        "DELETE FROM metadata WHERE key = 'traversal_last_frame'",
        "INSERT INTO frames SELECT id + 100, stamp_ns, frame_id, sequence, descriptor FROM frames WHERE id = 1",
        // Emptied and refilled to the same size (ids start again at 1), as after a reset, by a camera.
        "CREATE TABLE refill AS SELECT * FROM frames; DELETE FROM frames; "
        "INSERT INTO frames SELECT id, stamp_ns + 7, frame_id, sequence, descriptor FROM refill; DROP TABLE refill"}) {
    SCOPED_TRACE(change);
    const std::string file = recordedMap("changed.db");
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(file.c_str(), &db), SQLITE_OK);
    EXPECT_EQ(sqlite3_exec(db, change.c_str(), nullptr, nullptr, nullptr), SQLITE_OK);
    sqlite3_close(db);
    EXPECT_FALSE(MapDatabase(file, MapAccess::kReadOnly).traversal().has_value());
    {
      // Such a map is written as any other: the record read as none is replaced, not in the way.
      MapDatabase map(file, thumbnailParams());
      map.append(frames(1));
      MapTraversal traversal;
      traversal.frames = 20;
      map.setTraversal(traversal);
    }
    ASSERT_TRUE(MapDatabase(file, MapAccess::kReadOnly).traversal().has_value());
    EXPECT_EQ(MapDatabase(file, MapAccess::kReadOnly).traversal()->frames, 20);
    std::remove(file.c_str());
  }
  // A damaged appearance change alone leaves the frames known, the keyframing not.
  const std::string file = recordedMap("changed.db");
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(file.c_str(), &db), SQLITE_OK);
  EXPECT_EQ(sqlite3_exec(db, "UPDATE metadata SET value = '-1' WHERE key = 'traversal_min_appearance_change'", nullptr,
                         nullptr, nullptr),
            SQLITE_OK);
  sqlite3_close(db);
  const MapDatabase map(file, MapAccess::kReadOnly);
  ASSERT_TRUE(map.traversal().has_value());
  EXPECT_EQ(map.traversal()->frames, 8);
  EXPECT_FALSE(map.traversal()->min_appearance_change.has_value());
}

TEST_F(MapTraversalTest, AnAppearanceChangeIsWrittenAsAPersonReadsIt) {
  {
    MapDatabase map(path("tenth.db"), thumbnailParams());
    map.append(frames(2));
    MapTraversal traversal;
    traversal.frames = 2;
    traversal.min_appearance_change = 0.1;
    map.setTraversal(traversal);
  }
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path("tenth.db").c_str(), &db), SQLITE_OK);
  std::string value;
  sqlite3_exec(
      db, "SELECT value FROM metadata WHERE key = 'traversal_min_appearance_change'",
      [](void* out, int, char** values, char**) {
        *static_cast<std::string*>(out) = values[0];
        return 0;
      },
      &value, nullptr);
  sqlite3_close(db);
  EXPECT_EQ(value, "0.1");
  EXPECT_EQ(MapDatabase(path("tenth.db"), MapAccess::kReadOnly).traversal()->min_appearance_change, 0.1);
}

TEST(NextFrameNumber, GoesOnAfterTheLastNumberAndTheRecordedTraversalWithoutWrapping) {
  EXPECT_EQ(nextFrameNumber(-1), 0);
  EXPECT_EQ(nextFrameNumber(41), 42);
  MapTraversal traversal;
  traversal.frames = 111;  // Frames 109 and 110 were not kept: the next is 111, not 109.
  EXPECT_EQ(nextFrameNumber(108, traversal), 111);
  EXPECT_EQ(nextFrameNumber(200, traversal), 201);
  const std::int64_t largest = std::numeric_limits<std::int64_t>::max();
  EXPECT_EQ(nextFrameNumber(largest), largest);
}

TEST(FrameNumbering, GoesOnAfterTheLargestNumberAFrameWithoutOneCountingAsItsIndex) {
  EXPECT_EQ(FrameNumbering().next(), 0);  // An empty map.
  FrameNumbering unnumbered;              // A map saved before frames were numbered.
  for (int i = 0; i < 5; ++i) unnumbered.see(-1);
  EXPECT_EQ(unnumbered.next(), 5);
  FrameNumbering keyframed;  // Keyframes of frames 0..90, then one added without a number.
  for (const std::int64_t number : {0, 30, 60, 90, -1}) keyframed.see(number);
  EXPECT_EQ(keyframed.next(), 91);  // Not 5, the map's size: the next frames would repeat 30, 60 and 90.
  MapTraversal traversal;
  traversal.frames = 120;  // Frames 91..119 were offered and not kept.
  EXPECT_EQ(keyframed.next(traversal), 120);
  FrameNumbering unnumbered_last;  // Frame 3 has no number: it counts as 3, after 1 and 2.
  for (const std::int64_t number : {0, 1, 2, -1}) unnumbered_last.see(number);
  EXPECT_EQ(unnumbered_last.next(), 4);
}

TEST(KeyframingMismatch, IsSaidOnlyWhenTheMapRecordsAnotherAppearanceChange) {
  MapTraversal kept_at_04;
  kept_at_04.frames = 10;
  kept_at_04.min_appearance_change = 0.4;
  EXPECT_EQ(keyframingMismatch(kept_at_04, 0.4, "~min_appearance_change"), "");
  EXPECT_EQ(keyframingMismatch(std::nullopt, 0.0, "~min_appearance_change"), "");
  MapTraversal by_travel;
  by_travel.frames = 10;
  EXPECT_EQ(keyframingMismatch(by_travel, 0.0, "~min_appearance_change"), "");
  const std::string mismatch = keyframingMismatch(kept_at_04, 0.0, "~min_appearance_change");
  EXPECT_NE(mismatch.find("the map's keyframes were kept at an appearance change of 0.4, and ~min_appearance_change "
                          "is 0"),
            std::string::npos)
      << mismatch;
}

}  // namespace
}  // namespace mrs_vpr
