#include <grp.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <sqlite3.h>

#include "mrs_vpr/store/map_database.hpp"
#include "mrs_vpr/store/map_hold.hpp"
#include "support/crashed_writer.hpp"
#include "support/front_ends.hpp"
#include "support/temporary_folder.hpp"

namespace mrs_vpr {
namespace {

using testing_support::crashAfterCommitting;
using testing_support::thumbnailParams;

namespace fs = std::filesystem;
using testing_support::fileContents;

/// A fresh folder under the system's temporary directory, removed when the test ends.
class MapDatabaseTest : public ::testing::Test {
 protected:
  std::string path(const std::string& name) const { return folder_.path(name); }

  /// The rows of `sql` run on the database file `file`, opened read-only with SQLite itself; no
  /// rows (and a failure) when it cannot be opened.
  static std::vector<std::vector<std::string>> rowsOf(const std::string& file, const char* sql) {
    std::vector<std::vector<std::string>> rows;
    sqlite3* db = nullptr;
    const int opened = sqlite3_open_v2(file.c_str(), &db, SQLITE_OPEN_READONLY, nullptr);
    EXPECT_EQ(opened, SQLITE_OK) << file;
    if (opened == SQLITE_OK) {
      sqlite3_exec(
          db, sql,
          [](void* out, int columns, char** values, char**) {
            std::vector<std::string>& row = static_cast<std::vector<std::vector<std::string>>*>(out)->emplace_back();
            for (int c = 0; c < columns; ++c) row.emplace_back(values[c] != nullptr ? values[c] : "");  // NULL: "".
            return 0;
          },
          &rows, nullptr);
    }
    sqlite3_close(db);
    return rows;
  }

  /// The metadata table of the database file `file`, by key.
  static std::map<std::string, std::string> metadataOf(const std::string& file) {
    std::map<std::string, std::string> metadata;
    for (const auto& row : rowsOf(file, "SELECT key, value FROM metadata")) metadata[row[0]] = row[1];
    return metadata;
  }

  /// Frames whose descriptor bytes, stamps and ids all differ.
  static std::vector<StoredFrame> frames(int count, int first = 0) {
    std::vector<StoredFrame> result;
    cv::RNG rng(static_cast<std::uint64_t>(first) + 1);
    for (int i = first; i < first + count; ++i) {
      StoredFrame frame;
      frame.descriptor = cv::Mat(1, 64 * 32, CV_8UC1);
      rng.fill(frame.descriptor, cv::RNG::UNIFORM, 0, 256);
      frame.stamp = Stamp::fromNanoseconds(1'000'000'000'000 + 100'000'000LL * i);
      frame.frame_id = i % 2 == 0 ? "camera" : "";
      frame.sequence = i % 3 == 0 ? -1 : i;
      result.push_back(frame);
    }
    return result;
  }

  /// The message of the MapDatabaseError that opening `file` throws, or "(opened)".
  static std::string openingError(const std::string& file, const DescriptorParams& params = thumbnailParams()) {
    try {
      MapDatabase database(file, params);
    } catch (const MapDatabaseError& error) {
      return error.what();
    }
    return "(opened)";
  }


  testing_support::TemporaryFolder folder_{"mrs_vpr_store_test"};
};

TEST_F(MapDatabaseTest, FramesComeBackBitForBitInOrderAfterReopening) {
  const std::vector<StoredFrame> written = frames(120);
  {
    MapDatabase database(path("map.db"), thumbnailParams());
    database.append({written.begin(), written.begin() + 50});
    database.append({written.begin() + 50, written.end()});
    EXPECT_EQ(database.size(), 120);
  }
  const MapDatabase database(path("map.db"), thumbnailParams());
  std::size_t i = 0;
  database.forEachFrame([&](const StoredFrame& frame) {
    ASSERT_LT(i, written.size());
    EXPECT_EQ(cv::norm(frame.descriptor, written[i].descriptor, cv::NORM_L1), 0.0) << i;
    EXPECT_EQ(frame.stamp, written[i].stamp);
    EXPECT_EQ(frame.frame_id, written[i].frame_id);
    EXPECT_EQ(frame.sequence, written[i].sequence);
    ++i;
  });
  EXPECT_EQ(i, written.size());
}

TEST_F(MapDatabaseTest, APathWithANulByteIsRefusedRatherThanCutShort) {
  // The system would open "map.db" for "map.db\0junk": the map beside it, or a new file of that name.
  { MapDatabase existing(path("map.db"), thumbnailParams()); }
  const std::string cut = path("map.db") + std::string(1, '\0') + "junk";
  const std::string message = openingError(cut);
  EXPECT_NE(message.find("map path '" + path("map.db") + "' is followed by a NUL byte"), std::string::npos) << message;
  try {
    MapDatabase::checkSaveTarget(path("new.db") + std::string(1, '\0') + ".db");
    ADD_FAILURE() << "a path with a NUL byte was taken";
  } catch (const MapDatabaseError& error) {
    EXPECT_NE(std::string(error.what()).find("cannot save the map: map path"), std::string::npos) << error.what();
  }
}

TEST_F(MapDatabaseTest, ANewMapTakesLittleMoreDiskThanItsDescriptors) {
  // With SQLite's default 4 KiB pages each 2 KiB descriptor took a page of its own.
  {
    MapDatabase database(path("map.db"), thumbnailParams());
    database.append(frames(1000));
  }
  const auto page_size = rowsOf(path("map.db"), "PRAGMA page_size");
  ASSERT_EQ(page_size.size(), 1U);
  EXPECT_EQ(std::atoi(page_size[0][0].c_str()), MapDatabase::kPageSize);
  EXPECT_LT(fs::file_size(path("map.db")), 1000 * 2048 * 125 / 100);  // 4 KiB pages: 200%
}

TEST_F(MapDatabaseTest, MetadataNamesTheFormatAndTheDescriptorParameters) {
  { MapDatabase database(path("map.db"), thumbnailParams()); }
  std::map<std::string, std::string> metadata = metadataOf(path("map.db"));
  EXPECT_EQ(metadata["format_version"], "3");
  EXPECT_EQ(metadata["descriptor_type"], "thumbnail");
  EXPECT_EQ(metadata["image_width"], "64");
  EXPECT_EQ(metadata["image_height"], "32");
  EXPECT_EQ(metadata["patch_size"], "8");
  EXPECT_EQ(metadata["descriptor_bytes"], "2048");
  EXPECT_FALSE(metadata["created"].empty());
  EXPECT_FALSE(metadata["package_version"].empty());
}

TEST_F(MapDatabaseTest, AMapOfOtherDescriptorsIsRefusedNamingTheMismatch) {
  {
    MapDatabase database(path("map.db"), thumbnailParams());
    database.append(frames(3));
  }
  DescriptorParams other = thumbnailParams();
  other.image_width = 32;
  const std::string message = openingError(path("map.db"), other);
  EXPECT_NE(message.find(path("map.db")), std::string::npos) << message;
  EXPECT_NE(message.find("it holds descriptors of the thumbnail (64 x 32, patches of 8 px) front end, not of the "
                         "thumbnail (32 x 32, patches of 8 px) front end asked for"),
            std::string::npos)
      << message;
  EXPECT_EQ(MapDatabase(path("map.db"), thumbnailParams()).size(), 3);  // Untouched.
}

// Patches of another size give descriptors of the same size that mean something else.
TEST_F(MapDatabaseTest, AThumbnailMapOfOtherPatchesIsRefusedThoughItsDescriptorsHaveTheSameSize) {
  {
    MapDatabase database(path("map.db"), thumbnailParams());
    database.append(frames(3));
  }
  DescriptorParams other = thumbnailParams();
  other.patch_size = 4;
  ASSERT_EQ(other.descriptorSize(), thumbnailParams().descriptorSize());
  const std::string message = openingError(path("map.db"), other);
  EXPECT_NE(message.find("(64 x 32, patches of 8 px) front end, not of the thumbnail (64 x 32, patches of 4 px)"),
            std::string::npos)
      << message;
}

TEST_F(MapDatabaseTest, AHogMapRecordsItsFrontEndAndAThumbnailReaderIsRefusedNamingBoth) {
  DescriptorParams hog;
  hog.hog_blur = 1.5;
  {
    MapDatabase database(path("hog.db"), hog);
    StoredFrame frame;
    frame.descriptor = cv::Mat(1, hog.descriptorSize(), CV_8UC1, cv::Scalar(9));
    database.append({frame, frame});
  }
  std::map<std::string, std::string> metadata = metadataOf(path("hog.db"));
  EXPECT_EQ(metadata["descriptor_type"], "hog");
  EXPECT_EQ(metadata["hog_window_width"], "128");
  EXPECT_EQ(metadata["hog_window_height"], "64");
  EXPECT_EQ(metadata["hog_cell_size"], "16");
  EXPECT_EQ(metadata["hog_bins"], "9");
  EXPECT_EQ(metadata["hog_blur"], "1.5");
  EXPECT_EQ(metadata["descriptor_bytes"], "756");
  EXPECT_EQ(metadata.count("image_width"), 0U);
  EXPECT_EQ(MapDatabase(path("hog.db"), hog).size(), 2);
  const std::string message = openingError(path("hog.db"), thumbnailParams());
  EXPECT_NE(message.find("it holds descriptors of the hog (128 x 64 window, cells of 16 px, 9 bins, blur 1.5 px) "
                         "front end, not of the thumbnail (64 x 32, patches of 8 px) front end asked for"),
            std::string::npos)
      << message;
  hog.hog_blur = 2.0;
  EXPECT_NE(openingError(path("hog.db"), hog).find("blur 1.5 px"), std::string::npos);
}

TEST_F(MapDatabaseTest, AMapThatRecordsNoFrontEndHoldsThumbnails) {
  // Maps written before the front end could be chosen have no descriptor_type.
  {
    MapDatabase database(path("map.db"), thumbnailParams());
    database.append(frames(3));
  }
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path("map.db").c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db, "DELETE FROM metadata WHERE key = 'descriptor_type'", nullptr, nullptr, nullptr),
            SQLITE_OK);
  sqlite3_close(db);
  EXPECT_EQ(MapDatabase(path("map.db"), thumbnailParams()).size(), 3);
  EXPECT_NE(openingError(path("map.db"), DescriptorParams{}).find("thumbnail (64 x 32, patches of 8 px) front end"),
            std::string::npos);
}

TEST_F(MapDatabaseTest, AFrontEndRecordedIncompletelyIsRefusedSayingSo) {
  {
    MapDatabase database(path("map.db"), thumbnailParams());
  }
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path("map.db").c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db, "UPDATE metadata SET value = 'wide' WHERE key = 'image_width'", nullptr, nullptr, nullptr),
            SQLITE_OK);
  sqlite3_close(db);
  EXPECT_NE(openingError(path("map.db")).find("parameters of its front end are missing or not numbers"),
            std::string::npos);
}

TEST_F(MapDatabaseTest, AFileThatIsNotSqliteIsRefusedAndLeftUntouched) {
  {
    std::ofstream text(path("notes.db"));
    text << "my notes, not a map\n";
  }
  const std::string message = openingError(path("notes.db"));
  EXPECT_NE(message.find(path("notes.db")), std::string::npos) << message;
  EXPECT_NE(message.find("not a database"), std::string::npos) << message;
  EXPECT_EQ(fileContents(path("notes.db")), "my notes, not a map\n");
}

TEST_F(MapDatabaseTest, AnotherSqliteDatabaseIsRefusedAndLeftUntouched) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path("other.db").c_str(), &db), SQLITE_OK);
  sqlite3_exec(db, "CREATE TABLE recipes (name TEXT); INSERT INTO recipes VALUES ('bread')", nullptr, nullptr, nullptr);
  sqlite3_close(db);
  const std::string before = fileContents(path("other.db"));
  const std::string message = openingError(path("other.db"));
  EXPECT_NE(message.find("another kind"), std::string::npos) << message;
  EXPECT_EQ(fileContents(path("other.db")), before);
}

TEST_F(MapDatabaseTest, ATruncatedMapIsReportedNotReadAsEmpty) {
  {
    MapDatabase database(path("map.db"), thumbnailParams());
    database.append(frames(400));
  }
  fs::resize_file(path("map.db"), fs::file_size(path("map.db")) / 2);
  std::string message;
  try {
    const MapDatabase database(path("map.db"), thumbnailParams());
    database.forEachFrame([](const StoredFrame&) {});
    message = "(read " + std::to_string(database.size()) + " frames)";
  } catch (const MapDatabaseError& error) {
    message = error.what();
  }
  EXPECT_NE(message.find(path("map.db")), std::string::npos) << message;
  EXPECT_NE(message.find("malformed"), std::string::npos) << message;
}

TEST_F(MapDatabaseTest, AHeavilyDamagedMapIsReportedInOneShortMessage) {
  {
    MapDatabase database(path("map.db"), thumbnailParams());
    database.append(frames(3000));
  }
  fs::resize_file(path("map.db"), fs::file_size(path("map.db")) / 10);
  // As a file written by a tool that does not keep the size in the header valid: SQLite then takes the
  // size from the file and lists every missing page, thousands of bytes.
  {
    std::fstream file(path("map.db"), std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(92);
    file.write("\0\0\0\x09", 4);
  }
  std::string message;
  try {
    const MapDatabase database(path("map.db"), thumbnailParams(), MapAccess::kReadOnly);
    database.checkIntegrity();
    message = "(sound)";
  } catch (const MapDatabaseError& error) {
    message = error.what();
  }
  EXPECT_NE(message.find(path("map.db")), std::string::npos) << message;
  EXPECT_NE(message.find("it is corrupt or truncated (SQLite's quick_check finds at least 10 problems; the first: "),
            std::string::npos)
      << message;
  EXPECT_LT(message.size(), 300U) << message;
}

TEST_F(MapDatabaseTest, PathsThatCannotHoldAMapAreNamedForWhatTheyAre) {
  fs::create_directory(path("folder"));
  const std::string long_name = path(std::string(300, 'a') + ".db");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {path("folder"), "it is a folder, not a map file"},
      {long_name, "its file name is 303 bytes long, too long for this file system: at most 247"},
      {path("missing/map.db"), "there is no folder " + path("missing")},
  };
  for (const auto& [file, problem] : cases) {
    SCOPED_TRACE(file);
    const std::string message = openingError(file);
    EXPECT_NE(message.find(problem), std::string::npos) << message;
    std::string read_only;
    try {
      MapDatabase database(file, thumbnailParams(), MapAccess::kReadOnly);
    } catch (const MapDatabaseError& error) {
      read_only = error.what();
    }
    EXPECT_NE(read_only.find(file == path("folder") ? problem : "there is no such file"), std::string::npos)
        << read_only;
  }
  // A name that fits the file system but not beside the copy a save writes first.
  const std::vector<std::pair<std::string, std::string>> saves = {
      {path("folder"), "it is a folder (give the path of a new file in it, such as " + path("folder/map.db") + ")"},
      {path(std::string(245, 'b')), "its file name is 245 bytes long, too long for this file system: at most 241"},
      {path("missing/map.db"), "there is no folder " + path("missing")},
      // As typed into a service request, which no shell expands.
      {"~/mrs_vpr_no_such_folder/map.db", "there is no folder " + fs::absolute("~/mrs_vpr_no_such_folder").string() +
                                              " (~ is not expanded to a home folder here: give the path in full)"},
  };
  for (const auto& [file, problem] : saves) {
    SCOPED_TRACE(file);
    std::string message;
    try {
      MapDatabase::checkSaveTarget(file);
    } catch (const MapDatabaseError& error) {
      message = error.what();
    }
    EXPECT_NE(message.find("cannot save the map to '" + file + "': " + problem), std::string::npos) << message;
  }
  EXPECT_NO_THROW(MapDatabase::checkSaveTarget(path(std::string(241, 'c'))));
}

TEST_F(MapDatabaseTest, TheWriteAheadLogStaysSmallWhateverTheCommits) {
  // 600 commits of one frame each, as a node with a short commit period makes: at 64 KiB pages
  // SQLite's defaults let the log beside the map reach 64 MiB and stay there.
  MapDatabase database(path("map.db"), thumbnailParams());
  const std::vector<StoredFrame> written = frames(600);
  std::uintmax_t largest = 0;
  for (const StoredFrame& frame : written) {
    database.append({frame});
    std::error_code missing;
    largest = std::max(largest, fs::file_size(path("map.db-wal"), missing) * (missing ? 0 : 1));
  }
  std::printf("[ figures  ] log beside a map of 600 frames committed one by one: at most %.1f MiB\n",
              static_cast<double>(largest) / (1024.0 * 1024.0));
  // A checkpoint's worth of pages and the commit that passed it.
  EXPECT_LE(largest, static_cast<std::uintmax_t>(MapDatabase::kWalSizeLimit + 4 * (MapDatabase::kPageSize + 24)));
  EXPECT_GT(largest, 0U);
  EXPECT_EQ(database.size(), 600);
}

TEST_F(MapDatabaseTest, ASecondOwnerIsRefusedWhileTheFirstHoldsTheMap) {
  MapDatabase first(path("map.db"), thumbnailParams());
  first.append(frames(2));
  const std::string message = openingError(path("map.db"));
  EXPECT_NE(message.find("locked by another process"), std::string::npos) << message;
  first.append(frames(1, 2));  // The first owner goes on.
  EXPECT_EQ(first.size(), 3);
}

TEST_F(MapDatabaseTest, EveryCommittedFrameSurvivesAKillAtAnyMoment) {
  // A child appends batches and reports each committed total through a pipe; the parent kills it
  // with SIGKILL at seeded moments. Reopened, the map holds at least every reported frame, bit for
  // bit, and passes SQLite's integrity check.
  std::mt19937 rng(3);
  for (int round = 0; round < 5; ++round) {
    const std::string file = path("crash" + std::to_string(round) + ".db");
    int report[2];
    ASSERT_EQ(pipe(report), 0);
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      close(report[0]);
      MapDatabase database(file, thumbnailParams());
      for (int batch = 0;; ++batch) {
        database.append(frames(10, 10 * batch));
        const std::int64_t total = 10 * (batch + 1);
        if (write(report[1], &total, sizeof(total)) != sizeof(total)) _exit(1);
      }
    }
    close(report[1]);
    // The seeded moment counts from the first commit, however slow the machine: a sanitized build
    // under load sometimes took longer than the shortest delay to commit its first batch.
    std::int64_t persisted = 0;
    const bool committed = read(report[0], &persisted, sizeof(persisted)) == sizeof(persisted);
    if (committed) usleep(std::uniform_int_distribution<int>(20000, 200000)(rng));
    kill(child, SIGKILL);
    waitpid(child, nullptr, 0);
    std::int64_t total = 0;
    while (read(report[0], &total, sizeof(total)) == sizeof(total)) persisted = total;
    close(report[0]);
    ASSERT_TRUE(committed) << "the child stopped before its first commit";

    {
      const MapDatabase database(file, thumbnailParams());
      EXPECT_GE(database.size(), persisted);
      std::size_t i = 0;
      database.forEachFrame([&](const StoredFrame& frame) {
        // Batch b was written as frames(10, 10 b): recompute each batch the same way.
        const std::vector<StoredFrame> batch = frames(10, static_cast<int>(i / 10) * 10);
        EXPECT_EQ(cv::norm(frame.descriptor, batch[i % 10].descriptor, cv::NORM_L1), 0.0) << "frame " << i;
        EXPECT_EQ(frame.stamp, batch[i % 10].stamp);
        ++i;
      });
    }  // Closed: it holds the map exclusively while open.
    const auto integrity = rowsOf(file, "PRAGMA integrity_check");
    ASSERT_EQ(integrity.size(), 1U);
    EXPECT_EQ(integrity[0][0], "ok");
  }
}

TEST_F(MapDatabaseTest, ASnapshotIsNotSavedWhereAnEarlierMapLeftItsLog) {
  // The log of a map killed at that path, whose file was then removed (as the refusal to overwrite
  // it says): SQLite would read the log into the snapshot saved there.
  ASSERT_NO_FATAL_FAILURE(crashAfterCommitting(path("snapshot.db"), frames(5), thumbnailParams()));
  fs::remove(path("snapshot.db"));
  MapDatabase map(path("map.db"), thumbnailParams());
  map.append(frames(3, 10));
  std::string message;
  try {
    map.backupTo(path("snapshot.db"));
  } catch (const MapDatabaseError& error) {
    message = error.what();
  }
  EXPECT_NE(message.find("'" + path("snapshot.db") + "-wal' is left beside it by an earlier map of that name"),
            std::string::npos)
      << message;
  EXPECT_FALSE(fs::exists(path("snapshot.db")));
  fs::remove(path("snapshot.db-wal"));
  map.backupTo(path("snapshot.db"));
  EXPECT_EQ(MapDatabase(path("snapshot.db"), MapAccess::kReadOnly).size(), 3);
}

TEST_F(MapDatabaseTest, AMapOrSnapshotThatCannotBeCreatedSaysWhy) {
  MapDatabase map(path("map.db"), thumbnailParams());
  map.append(frames(3));
  const auto messageOf = [&](const std::string& target) {
    try {
      map.backupTo(target);
    } catch (const MapDatabaseError& error) {
      return std::string(error.what());
    }
    return std::string("(no error)");
  };
  // Where the snapshot is written before it is renamed, a folder or a file of the user's: named, and
  // left alone. An unfinished snapshot an earlier save left there is replaced.
  fs::create_directories(path("folder.db.part"));
  std::ofstream(path("notes.db.part")) << "mine\n";
  for (const std::string& name : {"folder.db", "notes.db"}) {
    const std::string in_the_way = messageOf(path(name));
    EXPECT_NE(in_the_way.find("'" + path(name + ".part") + "', which the map is written to on its way there, is a "
                              "folder or a file other than an unfinished map"),
              std::string::npos)
        << in_the_way;
    EXPECT_FALSE(fs::exists(path(name)));
  }
  EXPECT_TRUE(fs::is_directory(path("folder.db.part")));
  EXPECT_EQ(fileContents(path("notes.db.part")), "mine\n");
  map.backupTo(path("unfinished.db.part"));  // An earlier snapshot's copy, as if it had stopped there.
  std::ofstream(path("empty.db.part")).close();
  for (const std::string& name : {"unfinished.db", "empty.db"}) {
    EXPECT_NO_THROW(map.backupTo(path(name))) << name;
    EXPECT_EQ(MapDatabase(path(name), MapAccess::kReadOnly).size(), 3) << name;
  }
  // A folder where no file can be created: the system's reason, not SQLite's "unable to open".
  const std::string not_created = messageOf("/proc/snapshot.db");
  EXPECT_NE(not_created.find("cannot create '/proc/snapshot.db.part'"), std::string::npos) << not_created;
  EXPECT_EQ(not_created.find("unable to open database file"), std::string::npos) << not_created;
  // Nor is a map that cannot be created there opened with SQLite's words alone.
  try {
    MapDatabase("/proc/new.db", thumbnailParams());
    ADD_FAILURE() << "a map was created in /proc";
  } catch (const MapDatabaseError& error) {
    EXPECT_NE(std::string(error.what()).find("(No such file or directory)"), std::string::npos) << error.what();
  }
}

TEST_F(MapDatabaseTest, AHeldMapIsToldFromOneNobodyHolds) {
  EXPECT_NO_THROW(MapDatabase::checkNotHeld(path("missing.db")));
  std::ofstream(path("notes.db")) << "my notes, not a map\n";
  EXPECT_NO_THROW(MapDatabase::checkNotHeld(path("notes.db")));
  {
    MapDatabase held(path("map.db"), thumbnailParams());
    held.append(frames(2));
    try {
      MapDatabase::checkNotHeld(path("map.db"));
      ADD_FAILURE() << "a held map was not told";
    } catch (const MapDatabaseError& error) {
      EXPECT_NE(std::string(error.what()).find("it is held by another process"), std::string::npos) << error.what();
    }
    held.append(frames(1, 2));  // The owner goes on.
  }
  EXPECT_NO_THROW(MapDatabase::checkNotHeld(path("map.db")));
  // A map whose writer was killed is held by nobody; its log is recovered, not lost.
  ASSERT_NO_FATAL_FAILURE(crashAfterCommitting(path("crashed.db"), frames(4), thumbnailParams()));
  EXPECT_NO_THROW(MapDatabase::checkNotHeld(path("crashed.db")));
  EXPECT_EQ(MapDatabase(path("crashed.db"), MapAccess::kReadOnly).size(), 4);
}

TEST_F(MapDatabaseTest, AHoldKeepsWritersOutLetsReadersInAndChangesNothing) {
  {
    MapDatabase database(path("map.db"), thumbnailParams());
    database.append(frames(5));
  }
  const std::string closed_cleanly = fileContents(path("map.db"));
  {
    const MapHold hold(path("map.db"));
    EXPECT_NE(openingError(path("map.db")).find("locked by another process"), std::string::npos);
    EXPECT_EQ(MapDatabase(path("map.db"), MapAccess::kReadOnly).size(), 5);
    EXPECT_THROW(MapHold second(path("map.db")), MapDatabaseError);
  }
  // A map in WAL mode with no log beside it gets none from the hold: SQLite's empty log and index go.
  EXPECT_EQ(fileContents(path("map.db")), closed_cleanly);
  EXPECT_FALSE(fs::exists(path("map.db-wal")));
  EXPECT_FALSE(fs::exists(path("map.db-shm")));
  EXPECT_EQ(openingError(path("map.db")), "(opened)");
  // A killed writer's log stays as it was, and so does the file: a failed tool leaves the map's bytes.
  ASSERT_NO_FATAL_FAILURE(crashAfterCommitting(path("crashed.db"), frames(4), thumbnailParams()));
  const std::string file = fileContents(path("crashed.db"));
  const std::string log = fileContents(path("crashed.db-wal"));
  { const MapHold hold(path("crashed.db")); }
  EXPECT_EQ(fileContents(path("crashed.db")), file);
  EXPECT_EQ(fileContents(path("crashed.db-wal")), log);
}

TEST_F(MapDatabaseTest, ASelfContainedMapIsOneFileThatCanBeRenamed) {
  {
    MapDatabase database(path("map.db.part"), thumbnailParams());
    database.append(frames(30));
    database.makeSelfContained();
    EXPECT_FALSE(fs::exists(path("map.db.part-wal")));
    fs::rename(path("map.db.part"), path("map.db"));
  }
  EXPECT_EQ(MapDatabase(path("map.db"), MapAccess::kReadOnly).size(), 30);
  EXPECT_EQ(rowsOf(path("map.db"), "PRAGMA integrity_check")[0][0], "ok");
}

TEST_F(MapDatabaseTest, AMapIsCheckedBeforeItIsWritten) {
  // A free list that points past the file: every frame still reads, but every later commit fails.
  // The header's first free-list trunk page (offset 32) and count of free pages (36), big-endian.
  {
    MapDatabase database(path("map.db"), thumbnailParams());
    database.append(frames(20));
  }
  {
    std::fstream file(path("map.db"), std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(32);
    file.write("\0\0\x27\x0f\0\0\0\x01", 8);
  }
  const std::string before = fileContents(path("map.db"));
  EXPECT_EQ(MapDatabase(path("map.db"), MapAccess::kReadOnly).size(), 20);  // Reading alone does not tell.
  const std::string message = openingError(path("map.db"));
  EXPECT_NE(message.find(path("map.db")), std::string::npos) << message;
  EXPECT_NE(message.find("it is corrupt or truncated"), std::string::npos) << message;
  EXPECT_EQ(fileContents(path("map.db")), before);
}

/// What `attempt` returns, run as nobody when the test runs as root, whom no permission stops.
std::string withoutPrivileges(const std::function<std::string()>& attempt) {
  if (geteuid() != 0) return attempt();
  int pipe_ends[2];
  if (pipe(pipe_ends) != 0) return "(no pipe)";
  const pid_t child = fork();
  if (child == 0) {
    close(pipe_ends[0]);
    constexpr uid_t kNobody = 65534;
    if (setgroups(0, nullptr) != 0 || setgid(kNobody) != 0 || setuid(kNobody) != 0) _exit(1);
    const std::string result = attempt();
    const bool written = write(pipe_ends[1], result.data(), result.size()) == static_cast<ssize_t>(result.size());
    _exit(written ? 0 : 1);
  }
  close(pipe_ends[1]);
  std::string result;
  char buffer[256];
  for (ssize_t got; (got = read(pipe_ends[0], buffer, sizeof(buffer))) > 0;) result.append(buffer, got);
  close(pipe_ends[0]);
  waitpid(child, nullptr, 0);
  return result;
}

/// What opening `file` read-only tells a user who may not write to its folder: "N frames" or the
/// error.
std::string readWithoutWriteAccess(const std::string& file) {
  return withoutPrivileges([&]() -> std::string {
    try {
      return std::to_string(MapDatabase(file, MapAccess::kReadOnly).size()) + " frames";
    } catch (const MapDatabaseError& error) {
      return error.what();
    }
  });
}

/// What writing a new map at `file`, or saving one there, tells a user who may not write to its folder.
std::string writeWithoutWriteAccess(const std::string& file, bool save) {
  return withoutPrivileges([&]() -> std::string {
    try {
      if (save) {
        MapDatabase::checkSaveTarget(file);
      } else {
        MapDatabase database(file, thumbnailParams());
      }
      return "(no error)";
    } catch (const MapDatabaseError& error) {
      return error.what();
    }
  });
}

TEST_F(MapDatabaseTest, AMapInAFolderNobodyMayWriteToIsReadAsItIs) {
  // As a map installed in a package's share/ or on a read-only mount: SQLite cannot create the index
  // that reading a map in WAL mode needs beside it. The reader is nobody when the test runs as root,
  // who must then be able to reach the temporary folder.
  if (geteuid() == 0) {
    for (fs::path folder = fs::path(path("")).parent_path().parent_path(); !folder.empty() && folder != "/";
         folder = folder.parent_path()) {
      if ((fs::status(folder).permissions() & fs::perms::others_exec) == fs::perms::none) {
        GTEST_SKIP() << folder << " cannot be entered by nobody";
      }
    }
  }
  fs::permissions(path(""), fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                                fs::perms::others_read | fs::perms::others_exec);
  const auto readOnly = [&](const std::string& folder) {
    fs::permissions(path(folder), fs::perms::owner_read | fs::perms::owner_exec | fs::perms::group_read |
                                      fs::perms::group_exec | fs::perms::others_read | fs::perms::others_exec);
  };
  fs::create_directory(path("shipped"));
  {
    MapDatabase database(path("shipped/map.db"), thumbnailParams());
    database.append(frames(7));
  }
  readOnly("shipped");
  EXPECT_EQ(readWithoutWriteAccess(path("shipped/map.db")), "7 frames");
  // A new map there cannot be written, and says why: SQLite's words were "unable to open database file
  // (No such file or directory)", and a save was refused only after the work.
  for (const bool save : {false, true}) {
    const std::string refused = writeWithoutWriteAccess(path("shipped/new.db"), save);
    EXPECT_NE(refused.find("the folder " + path("shipped") + " cannot be written to (Permission denied)"),
              std::string::npos)
        << refused;
  }
  // Through a link from a folder the reader may write to, and by a path that begins with two slashes.
  fs::create_directory(path("open"));
  fs::permissions(path("open"), fs::perms::all);
  fs::create_symlink(path("shipped/map.db"), path("open/link.db"));
  EXPECT_EQ(readWithoutWriteAccess(path("open/link.db")), "7 frames");
  EXPECT_EQ(readWithoutWriteAccess("/" + path("shipped/map.db")), "7 frames");
  // A link there to a map not written yet in a folder the user may write to (a node's ~database): the
  // file the link names is the one created, by SQLite or by a save, so both may.
  fs::create_directory(path("links"));
  fs::create_symlink(path("open/through_link.db"), path("links/map.db"));
  readOnly("links");
  EXPECT_EQ(writeWithoutWriteAccess(path("links/map.db"), true), "(no error)");
  EXPECT_EQ(writeWithoutWriteAccess(path("links/map.db"), false), "(no error)");
  EXPECT_TRUE(fs::is_regular_file(path("open/through_link.db")));
  EXPECT_TRUE(fs::is_symlink(path("links/map.db")));
  fs::permissions(path("links"), fs::perms::owner_all, fs::perm_options::add);
  // A log there can be read only through the index: said so, not "attempt to write a readonly database".
  fs::create_directory(path("crashed"));
  ASSERT_NO_FATAL_FAILURE(crashAfterCommitting(path("crashed/map.db"), frames(3), thumbnailParams()));
  readOnly("crashed");
  const std::string message = readWithoutWriteAccess(path("crashed/map.db"));
  EXPECT_NE(message.find("its write-ahead log '" + path("crashed/map.db") + "-wal' can be read only where SQLite may "
                         "write its index beside it"),
            std::string::npos)
      << message;
  fs::permissions(path("shipped"), fs::perms::owner_all, fs::perm_options::add);
  fs::permissions(path("crashed"), fs::perms::owner_all, fs::perm_options::add);
}

/// Runs `sql` on the database file `file`, as a user editing a map by hand would.
void editByHand(const std::string& file, const std::string& sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(file.c_str(), &db), SQLITE_OK);
  char* error = nullptr;
  EXPECT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error), SQLITE_OK) << (error ? error : "") << sql;
  sqlite3_free(error);
  sqlite3_close(db);
}

TEST_F(MapDatabaseTest, RowsAndMetadataOfTheWrongKindAreRefusedNamingThem) {
  const auto damaged = [&](const std::string& name, const std::string& sql) {
    {
      MapDatabase database(path(name), thumbnailParams());
      database.append(frames(3));
    }
    editByHand(path(name), sql);
    try {
      const MapDatabase database(path(name), thumbnailParams(), MapAccess::kReadOnly);
      database.forEachFrame([](const StoredFrame&) {});
    } catch (const MapDatabaseError& error) {
      return std::string(error.what());
    }
    return std::string("(read)");
  };
  // SQLite reads 'x' as the number 0 and text as the bytes of a descriptor.
  EXPECT_NE(damaged("sequence.db", "UPDATE frames SET sequence = 'x' WHERE id = 2")
                .find("frame 2 has a sequence number that is not an integer"),
            std::string::npos);
  EXPECT_NE(damaged("text.db", "UPDATE frames SET descriptor = CAST(descriptor AS TEXT) WHERE id = 3")
                .find("frame 3 holds a descriptor that is not a blob"),
            std::string::npos);
  EXPECT_NE(damaged("bytes.db", "UPDATE metadata SET value = '1234' WHERE key = 'descriptor_bytes'")
                .find("its descriptor_bytes is '1234', but its front end's descriptors are 2048 bytes"),
            std::string::npos);
  // Front ends that differ beyond the digits shown, or a blur that is no number, are told apart.
  DescriptorParams hog;
  hog.hog_blur = 0.5;
  {
    MapDatabase database(path("blur.db"), hog);
  }
  DescriptorParams almost = hog;
  almost.hog_blur = 0.5000000001;
  EXPECT_NE(openingError(path("blur.db"), almost).find("front end asked for (hog_blur 0.5 against 0.50000000010000001)"),
            std::string::npos)
      << openingError(path("blur.db"), almost);
  editByHand(path("blur.db"), "UPDATE metadata SET value = 'nan' WHERE key = 'hog_blur'");
  EXPECT_NE(openingError(path("blur.db"), hog).find("its front end is not valid"), std::string::npos)
      << openingError(path("blur.db"), hog);
}

TEST_F(MapDatabaseTest, DriveStartsAreRecordedInOrderOnceEachAndADamagedRecordIsNamed) {
  const std::string file = path("drives.db");
  {
    MapDatabase map(file, thumbnailParams());
    EXPECT_TRUE(map.driveStarts().empty());
    map.addDriveStart(0);  // the map's beginning: no junction
    map.addDriveStart(120);
    map.addDriveStart(40);
    map.addDriveStart(120);
    EXPECT_EQ(map.driveStarts(), (std::vector<int>{40, 120}));
  }
  EXPECT_EQ(MapDatabase(file, MapAccess::kReadOnly).driveStarts(), (std::vector<int>{40, 120}));
  for (const std::string damaged : {"40 x", "120 40", "0", "-3", "40  120", "99999999999", "", "40 ", " 40"}) {
    editByHand(file, "UPDATE metadata SET value = '" + damaged + "' WHERE key = 'drive_starts'");
    std::string message = "(read)";
    try {
      MapDatabase(file, MapAccess::kReadOnly).driveStarts();
    } catch (const MapDatabaseError& error) {
      message = error.what();
    }
    EXPECT_NE(message.find("its drive_starts '" + damaged + "' is not a list of ascending frame numbers; with no "
                           "node holding the map, sqlite3 '" + file +
                           "' \"DELETE FROM metadata WHERE key = 'drive_starts'\" removes it"),
              std::string::npos)
        << message;
  }
  {
    MapDatabase map(file, thumbnailParams());
    map.clear();
    EXPECT_TRUE(map.driveStarts().empty());
    map.addDriveStart(7);
    map.replace([](const auto&) {}, std::nullopt, {}, {3, 5});
    EXPECT_EQ(map.driveStarts(), (std::vector<int>{3, 5}));
  }
}

TEST_F(MapDatabaseTest, ClearEmptiesTheFramesAndKeepsTheMetadata) {
  {
    MapDatabase database(path("map.db"), thumbnailParams());
    database.append(frames(5));
    database.clear();
    EXPECT_EQ(database.size(), 0);
    database.append(frames(1));
    EXPECT_EQ(database.size(), 1);
  }  // Closed: it holds the map exclusively while open.
  std::map<std::string, std::string> metadata = metadataOf(path("map.db"));
  EXPECT_EQ(metadata["format_version"], "3");
  EXPECT_EQ(metadata["descriptor_type"], "thumbnail");
  EXPECT_EQ(metadata["descriptor_bytes"], "2048");
  // And the map is still one of these descriptors: another front end's is refused.
  EXPECT_THROW(MapDatabase(path("map.db"), DescriptorParams{}), MapDatabaseError);  // HOG, the default
}

TEST_F(MapDatabaseTest, BadDescriptorsAreRefusedBeforeAnythingIsWritten) {
  MapDatabase database(path("map.db"), thumbnailParams());
  std::vector<StoredFrame> batch = frames(3);
  batch[2].descriptor = cv::Mat(1, 10, CV_8UC1);
  EXPECT_THROW(database.append(batch), std::invalid_argument);
  EXPECT_EQ(database.size(), 0);
}

// replace() takes its frames from a source read as it goes (PersistentMap::load reads a file a second
// time), so it can meet a bad descriptor or a failure after some frames: the old frames must then stay,
// all of them, and none of the new ones.
TEST_F(MapDatabaseTest, AReplaceThatFailsPartWayKeepsEveryOldFrame) {
  MapDatabase database(path("map.db"), thumbnailParams());
  const std::vector<StoredFrame> old_frames = frames(3);
  database.append(old_frames);
  std::vector<StoredFrame> batch = frames(4, 10);
  batch[3].descriptor = cv::Mat(1, 10, CV_8UC1, cv::Scalar(0));
  const auto stampsOf = [&] {
    std::vector<Stamp> stamps;
    database.forEachFrame([&](const StoredFrame& frame) { stamps.push_back(frame.stamp); });
    return stamps;
  };
  const std::vector<Stamp> old_stamps = {old_frames[0].stamp, old_frames[1].stamp, old_frames[2].stamp};
  const MapDatabase::FrameSource with_bad_descriptor = [&](const auto& insert) {
    for (const StoredFrame& frame : batch) insert(frame);
  };
  EXPECT_THROW(database.replace(with_bad_descriptor), std::invalid_argument);
  EXPECT_EQ(stampsOf(), old_stamps);
  const MapDatabase::FrameSource failing = [&](const auto& insert) {
    insert(batch[0]);
    throw std::runtime_error("the source's file changed");
  };
  EXPECT_THROW(database.replace(failing), std::runtime_error);
  EXPECT_EQ(stampsOf(), old_stamps);
  database.replace([&](const auto& insert) { insert(batch[1]); });
  EXPECT_EQ(stampsOf(), std::vector<Stamp>{batch[1].stamp});
}

// A read that fails ends its read transaction: the connection then reads the file as it is now and
// can still write, rather than staying in the failed read's transaction.
TEST_F(MapDatabaseTest, AFailedReadAtOneMomentLeavesTheDatabaseReadableAndWritable) {
  MapDatabase database(path("map.db"), thumbnailParams());
  database.append(frames(2));
  const auto failing_read = [&] {
    EXPECT_EQ(database.size(), 2);
    throw std::runtime_error("a reader's failure");
  };
  EXPECT_THROW(database.readAtOneMoment(failing_read), std::runtime_error);
  database.append(frames(1, 2));
  std::int64_t size = 0;
  database.readAtOneMoment([&] { size = database.size(); });
  EXPECT_EQ(size, 3);
}

TEST_F(MapDatabaseTest, ALongFileOfTheUsersWhereTheSnapshotIsWrittenFirstIsLeftAlone) {
  MapDatabase map(path("map.db"), thumbnailParams());
  map.append(frames(3));
  // Longer than SQLite's 16-byte header, but not an SQLite file: the user's, not an unfinished map.
  const std::string notes = "These notes are not a map, and longer than sixteen bytes.\n";
  std::ofstream(path("notes.db.part")) << notes;
  try {
    map.backupTo(path("notes.db"));
    ADD_FAILURE() << "the snapshot was written over notes.db.part";
  } catch (const MapDatabaseError& error) {
    EXPECT_NE(std::string(error.what()).find("is a folder or a file other than an unfinished map"), std::string::npos)
        << error.what();
  }
  EXPECT_EQ(fileContents(path("notes.db.part")), notes);
  EXPECT_FALSE(fs::exists(path("notes.db")));
}

TEST_F(MapDatabaseTest, NamesThatSqliteWouldReadAsMemoryOrAUriAreFiles) {
  // ":memory:" gave a map that was never written, and "file:uri.db" one written to uri.db.
  const fs::path previous = fs::current_path();
  fs::current_path(fs::path(path("anything")).parent_path());
  for (const std::string name : {":memory:", "file:uri.db"}) {
    SCOPED_TRACE(name);
    MapDatabase(name, thumbnailParams()).append(frames(3));
    EXPECT_TRUE(fs::is_regular_file(name));
    EXPECT_EQ(MapDatabase(name, MapAccess::kReadOnly).size(), 3);
  }
  EXPECT_FALSE(fs::exists("uri.db"));
  fs::current_path(previous);
}

TEST_F(MapDatabaseTest, AHogCellOfNoSizeIsRefusedNotDividedBy) {
  DescriptorParams params;
  params.hog_cell_size = 0;
  try {
    MapDatabase map(path("cells.db"), params);
    ADD_FAILURE() << "opened";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("descriptor/hog/cell_size"), std::string::npos) << error.what();
  }
  EXPECT_FALSE(fs::exists(path("cells.db")));
}

}  // namespace
}  // namespace mrs_vpr
