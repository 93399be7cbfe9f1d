// The map database's stamps: exact nanoseconds since format 2, up to the latest ROS time; maps of
// format 1 (REAL seconds, written by earlier releases) read and converted; a stamp that no ROS time
// can hold is an error naming the frame, never a frame a node cannot publish.

#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <sqlite3.h>

#include "mrs_vpr/store/map_database.hpp"
#include "mrs_vpr/store/persistent_map.hpp"
#include "support/format_one_map.hpp"
#include "support/front_ends.hpp"
#include "support/temporary_folder.hpp"

namespace mrs_vpr {
namespace {

using testing_support::thumbnailParams;

using testing_support::fileContents;
using testing_support::runSql;
using testing_support::writeFormatOneMap;

constexpr int kDescriptorBytes = testing_support::kFormatOneDescriptorBytes;
const Stamp kLatest = Stamp::fromSecondsAndNanoseconds(4294967295U, 999999999U);

std::vector<StoredFrame> framesOf(const MapDatabase& database) {
  std::vector<StoredFrame> frames;
  database.forEachFrame([&](const StoredFrame& frame) {
    frames.push_back({frame.descriptor.clone(), frame.stamp, frame.frame_id, frame.sequence});
  });
  return frames;
}

/// The message of the MapDatabaseError that `action` throws, or "(no error)".
template <typename Action>
std::string errorOf(Action action) {
  try {
    action();
  } catch (const MapDatabaseError& error) {
    return error.what();
  }
  return "(no error)";
}

class MapFormatTest : public ::testing::Test {
 protected:
  std::string path(const std::string& name) const { return folder_.path(name); }

  testing_support::TemporaryFolder folder_{"mrs_vpr_map_format_test"};
};

TEST_F(MapFormatTest, StampsComeBackExactUpToTheLatestRosTime) {
  const std::vector<Stamp> stamps = {Stamp(), Stamp::fromSecondsAndNanoseconds(1700000000U, 123456789U),
                                     Stamp::fromSecondsAndNanoseconds(1700000000U, 123456790U), kLatest};
  {
    MapDatabase database(path("map.db"), thumbnailParams());
    std::vector<StoredFrame> frames;
    for (const Stamp stamp : stamps) {
      frames.push_back({cv::Mat(1, kDescriptorBytes, CV_8UC1, cv::Scalar(3)), stamp, "", -1});
    }
    database.append(frames);
  }
  const std::vector<StoredFrame> read = framesOf(MapDatabase(path("map.db"), thumbnailParams(), MapAccess::kReadOnly));
  ASSERT_EQ(read.size(), stamps.size());
  for (std::size_t i = 0; i < stamps.size(); ++i) EXPECT_EQ(read[i].stamp, stamps[i]) << i;
}

TEST_F(MapFormatTest, AFormatOneMapIsReadWithItsStampsToTheNearestNanosecond) {
  writeFormatOneMap(path("old.db"), {1000.1, 1700000000.25, 0.0});
  const std::string before = fileContents(path("old.db"));
  const std::vector<StoredFrame> read = framesOf(MapDatabase(path("old.db"), thumbnailParams(), MapAccess::kReadOnly));
  ASSERT_EQ(read.size(), 3U);
  EXPECT_EQ(read[0].stamp.nanoseconds(), 1000100000000);
  EXPECT_EQ(read[1].stamp.nanoseconds(), 1700000000250000000);
  EXPECT_EQ(read[2].stamp, Stamp());
  EXPECT_EQ(read[1].descriptor.at<std::uint8_t>(0, 100), 1);
  EXPECT_EQ(read[1].frame_id, "camera");
  EXPECT_EQ(read[1].sequence, 1);
  EXPECT_TRUE(fileContents(path("old.db")) == before) << "a read-only map was changed";
}

TEST_F(MapFormatTest, AFormatOneMapOpenedForWritingIsConvertedInPlace) {
  writeFormatOneMap(path("old.db"), {1000.1, 1700000000.25});
  {
    MapDatabase database(path("old.db"), thumbnailParams());
    database.append({{cv::Mat(1, kDescriptorBytes, CV_8UC1, cv::Scalar(9)), kLatest, "", -1}});
  }
  const MapDatabase database(path("old.db"), thumbnailParams(), MapAccess::kReadOnly);
  const std::vector<StoredFrame> read = framesOf(database);
  ASSERT_EQ(read.size(), 3U);
  EXPECT_EQ(read[0].stamp.nanoseconds(), 1000100000000);
  EXPECT_EQ(read[1].stamp.nanoseconds(), 1700000000250000000);
  EXPECT_EQ(read[1].descriptor.at<std::uint8_t>(0, 7), 1);
  EXPECT_EQ(read[2].stamp, kLatest);
  // The file is of format 3 now, as a new map is.
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open_v2(path("old.db").c_str(), &db, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
  sqlite3_stmt* statement = nullptr;
  ASSERT_EQ(sqlite3_prepare_v2(db,
                               "SELECT (SELECT value FROM metadata WHERE key = 'format_version'),"
                               " (SELECT typeof(stamp_ns) FROM frames WHERE id = 2),"
                               " (SELECT stamp_ns FROM frames WHERE id = 2)",
                               -1, &statement, nullptr),
            SQLITE_OK);
  ASSERT_EQ(sqlite3_step(statement), SQLITE_ROW);
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(sqlite3_column_text(statement, 0))), "3");
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(sqlite3_column_text(statement, 1))), "integer");
  EXPECT_EQ(sqlite3_column_int64(statement, 2), 1700000000250000000);
  sqlite3_finalize(statement);
  sqlite3_close(db);
}

TEST_F(MapFormatTest, AStampNoRosTimeCanHoldIsAnErrorNamingTheFrame) {
  int round = 0;
  for (const double stamp : {1e30, -5.0, 4294967296.0}) {
    SCOPED_TRACE(stamp);
    const std::string file = path("old" + std::to_string(round++) + ".db");
    writeFormatOneMap(file, {1000.0, stamp, 1002.0});
    const std::string before = fileContents(file);
    std::string message = errorOf([&] { framesOf(MapDatabase(file, thumbnailParams(), MapAccess::kReadOnly)); });
    EXPECT_NE(message.find(file), std::string::npos) << message;
    EXPECT_NE(message.find("frame 2 has an unusable stamp"), std::string::npos) << message;
    EXPECT_NE(message.find("outside 0 .. 4294967295.999999999 s"), std::string::npos) << message;
    // Opened for writing: the conversion fails and leaves the file as it was.
    message = errorOf([&] { MapDatabase database(file, thumbnailParams()); });
    EXPECT_NE(message.find("cannot convert it from format 1 to 3 (it is left as it was)"), std::string::npos)
        << message;
    EXPECT_NE(message.find("frame 2 has an unusable stamp"), std::string::npos) << message;
    EXPECT_TRUE(fileContents(file) == before) << "the map was changed";
  }
  // A map of this format changed by hand: beyond the range, and not an integer.
  { MapDatabase database(path("map.db"), thumbnailParams()); }
  runSql(path("map.db"), "INSERT INTO frames VALUES (1, 4294967296000000000, '', -1, zeroblob(2048)),"
                         " (2, 'noon', '', -1, zeroblob(2048))");
  const MapDatabase database(path("map.db"), thumbnailParams(), MapAccess::kReadOnly);
  std::string message = errorOf([&] { framesOf(database); });
  EXPECT_NE(message.find("frame 1 has an unusable stamp: stamp 4294967296.000000000 s is outside"), std::string::npos)
      << message;
  runSql(path("map.db"), "DELETE FROM frames WHERE id = 1");
  message = errorOf([&] { framesOf(database); });
  EXPECT_NE(message.find("frame 2 has an unusable stamp: it is not an integer"), std::string::npos) << message;
}

TEST_F(MapFormatTest, APersistentMapRefusesAnUnusableStampAndKeepsItsMap) {
  writeFormatOneMap(path("bad.db"), {1000.0, 1e30});
  Parameters thumbnails;  // The front end of format-1 maps.
  thumbnails.descriptor = thumbnailParams();
  PlaceRecognizer recognizer(thumbnails);
  PersistentMap map(recognizer, path("map.db"), CommitPolicy{});
  map.add(cv::Mat(1, kDescriptorBytes, CV_8UC1, cv::Scalar(1)), kLatest);
  const std::string message = errorOf([&] { map.load(path("bad.db")); });
  EXPECT_NE(message.find("frame 2 has an unusable stamp"), std::string::npos) << message;
  EXPECT_EQ(recognizer.size(), 1);
  EXPECT_EQ(recognizer.state().last_stamp, kLatest);
  // Starting on it fails too, naming it, rather than with a map whose stamps cannot be published.
  PlaceRecognizer other(thumbnails);
  const std::string start = errorOf([&] { PersistentMap bad(other, path("bad.db"), CommitPolicy{}); });
  EXPECT_NE(start.find(path("bad.db")), std::string::npos) << start;
  EXPECT_NE(start.find("frame 2 has an unusable stamp"), std::string::npos) << start;
}

}  // namespace
}  // namespace mrs_vpr
