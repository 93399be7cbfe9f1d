// build_map replacing and extending maps that others hold, left behind or share a name with: a map
// it reports written is the one it wrote, and a failure leaves the map as it was.

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <csignal>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "mrs_vpr/parameters.hpp"
#include "mrs_vpr/stamp.hpp"
#include "mrs_vpr/store/map_database.hpp"
#include "route_tools_fixture.hpp"
#include "support/command_run.hpp"
#include "support/crashed_writer.hpp"
#include "support/format_one_map.hpp"
#include "support/front_ends.hpp"

namespace {

namespace fs = std::filesystem;
using mrs_vpr::MapAccess;
using mrs_vpr::MapDatabase;
using mrs_vpr::testing_support::CommandResult;
using mrs_vpr::testing_support::fileContents;

class BuildMapTest : public mrs_vpr::testing_support::RouteToolsTest {
 protected:
  /// The front end buildMap() writes.
  static mrs_vpr::DescriptorParams thumbnail() { return mrs_vpr::testing_support::thumbnailParams(); }

  /// `count` frames of thumbnail descriptors.
  static std::vector<mrs_vpr::StoredFrame> frames(int count) {
    std::vector<mrs_vpr::StoredFrame> result;
    for (int i = 0; i < count; ++i) {
      result.push_back({cv::Mat(1, thumbnail().descriptorSize(), CV_8UC1, cv::Scalar(i)),
                        mrs_vpr::Stamp::fromNanoseconds(1'000'000'000LL * (i + 1)), "", i});
    }
    return result;
  }

  static std::int64_t framesIn(const std::string& file) { return MapDatabase(file, MapAccess::kReadOnly).size(); }

  static std::string build(const std::string& output, const std::string& options = "") {
    return buildMap() + " --images " + path("reference") + " --output " + output + options;
  }
};

TEST_F(BuildMapTest, AMapReplacedWithForceTakesNothingFromTheOldOnesLog) {
  const std::string map = path("crashed.db");
  ASSERT_NO_FATAL_FAILURE(mrs_vpr::testing_support::crashAfterCommitting(map, frames(93), thumbnail()));
  const CommandResult replaced = run(build(map, " --force"));
  ASSERT_EQ(replaced.status, 0) << replaced.err;
  EXPECT_NE(replaced.err.find("150 frames added to 0"), std::string::npos) << replaced.err;
  EXPECT_FALSE(fs::exists(map + "-wal"));
  EXPECT_EQ(framesIn(map), 150);  // Not the 93 of the old log.
}

TEST_F(BuildMapTest, ALogLeftWhereTheMapIsToGoIsRefused) {
  const std::string map = path("removed.db");
  ASSERT_NO_FATAL_FAILURE(mrs_vpr::testing_support::crashAfterCommitting(map, frames(5), thumbnail()));
  fs::remove(map);
  const CommandResult refused = run(build(map));
  EXPECT_EQ(refused.status, 1);
  EXPECT_NE(refused.err.find("'" + map + "-wal' is left beside it by an earlier map of that name"), std::string::npos)
      << refused.err;
  EXPECT_FALSE(fs::exists(map));
}

TEST_F(BuildMapTest, AMapThatIsHeldIsNeitherReplacedNorExtended) {
  const std::string map = path("held.db");
  ASSERT_EQ(run(build(map)).status, 0);
  {
    MapDatabase node(map, thumbnail());  // As a node writing it.
    for (const std::string& option : {" --force", " --append"}) {
      const CommandResult refused = run(build(map, option));
      EXPECT_EQ(refused.status, 1) << option;
      EXPECT_NE(refused.err.find(map), std::string::npos) << option << ": " << refused.err;
      EXPECT_TRUE(refused.err.find("held by another process") != std::string::npos ||
                  refused.err.find("locked by another process") != std::string::npos)
          << option << ": " << refused.err;
      EXPECT_FALSE(fs::exists(map + ".part")) << option;
    }
    node.append(frames(2));  // The node goes on.
  }
  EXPECT_EQ(framesIn(map), 152);
}

TEST_F(BuildMapTest, AnotherRunsUnfinishedMapIsLeftToIt) {
  const std::string map = path("shared.db");
  {
    MapDatabase other(map + ".part", thumbnail());  // Another build_map, still writing.
    other.append(frames(3));
    const CommandResult refused = run(build(map));
    EXPECT_EQ(refused.status, 1);
    EXPECT_NE(refused.err.find(map + ".part': it is held by another process"), std::string::npos) << refused.err;
    EXPECT_TRUE(fs::exists(map + ".part"));
    other.append(frames(1));  // Its file is still its own.
  }
  EXPECT_FALSE(fs::exists(map));
}

TEST_F(BuildMapTest, AFileOfTheUsersWhereTheMapIsWrittenAsideIsLeftAlone) {
  const std::string map = path("notes.db");
  std::ofstream(map + ".part") << "my notes\n";
  const CommandResult refused = run(build(map));
  EXPECT_EQ(refused.status, 1);
  EXPECT_NE(refused.err.find(map + ".part', which the map is written to on its way there, is a folder or a file"),
            std::string::npos)
      << refused.err;
  EXPECT_EQ(fileContents(map + ".part"), "my notes\n");
  EXPECT_FALSE(fs::exists(map));
}

TEST_F(BuildMapTest, AFailedExtensionLeavesAMapOfAnEarlierFormatAsItWas) {
  const std::string map = path("format1.db");
  mrs_vpr::testing_support::writeFormatOneMap(map, {1.0, 2.0, 3.0});
  const std::string before = fileContents(map);
  const CommandResult failed =
      run(buildMap() + " --images " + path("no_such_folder") + " --output " + map + " --append");
  EXPECT_EQ(failed.status, 1);
  EXPECT_NE(failed.err.find("no_such_folder"), std::string::npos) << failed.err;
  EXPECT_EQ(fileContents(map), before);  // Neither converted to format 2 nor switched to a log.
  EXPECT_FALSE(fs::exists(map + ".part"));
  // A successful extension converts its copy.
  const CommandResult appended = run(build(map, " --append"));
  ASSERT_EQ(appended.status, 0) << appended.err;
  EXPECT_NE(appended.err.find("150 frames added to 3"), std::string::npos) << appended.err;
  EXPECT_EQ(framesIn(map), 153);
}

// A damaged record of the map is named by the map's own path, and the map is left as it was.
TEST_F(BuildMapTest, AnExtensionOfAMapWithADamagedRecordNamesTheMap) {
  const std::string map = path("damaged.db");
  {
    MapDatabase database(map, thumbnail());
    database.append(frames(3));
    database.addDriveStart(2);
  }
  mrs_vpr::testing_support::runSql(map, "UPDATE metadata SET value = '2 1' WHERE key = 'drive_starts'");
  const std::string before = fileContents(map);
  const CommandResult failed = run(build(map, " --append"));
  EXPECT_EQ(failed.status, 1);
  EXPECT_NE(failed.err.find("map database '" + map + "': its drive_starts '2 1' is not a list of ascending frame "
                            "numbers; with no node holding the map, sqlite3 '" + map + "'"),
            std::string::npos)
      << failed.err;
  EXPECT_EQ(fileContents(map), before);
  EXPECT_FALSE(fs::exists(map + ".part"));
}

TEST_F(BuildMapTest, AStoppedBuildLeavesNoUnfinishedMap) {
  const std::string map = path("stopped.db");
  const CommandResult stopped = run(mrs_vpr::testing_support::stoppedOnceExists(
      buildMap() + " --images " + manyFrames() + " --output " + map, map + ".part"));
  EXPECT_EQ(stopped.status, 128 + SIGTERM) << stopped.err;
  EXPECT_NE(stopped.err.find("build_map: interrupted by SIGTERM"), std::string::npos) << stopped.err;
  for (const char* file : {"", ".part", ".part-journal", ".part-wal", ".part-shm"}) {
    EXPECT_FALSE(fs::exists(map + file)) << map + file;
  }
}

TEST_F(BuildMapTest, ALinkToAnInputIsNoOutput) {
  // Through the link, the map would be written over one of the images it reads.
  fs::create_symlink(path("reference/00000.png"), path("to_input.db"));
  const CommandResult refused = run(build(path("to_input.db"), " --force"));
  EXPECT_EQ(refused.status, 1);
  EXPECT_NE(refused.err.find("lies inside the folder"), std::string::npos) << refused.err;
  EXPECT_TRUE(fs::is_symlink(path("to_input.db")));
}

TEST_F(BuildMapTest, AMapNamedThroughALinkIsExtendedWhereTheLinkPoints) {
  const std::string map = path("linked.db");
  ASSERT_EQ(run(build(map)).status, 0);
  fs::create_symlink(map, path("link.db"));
  const CommandResult appended = run(build(path("link.db"), " --append"));
  ASSERT_EQ(appended.status, 0) << appended.err;
  EXPECT_TRUE(fs::is_symlink(path("link.db")));
  EXPECT_EQ(framesIn(map), 300);
}

TEST_F(BuildMapTest, ALinkToAMapNotWrittenYetIsWrittenWhereItPoints) {
  // As a link to an existing map is: ~/maps/current.db -> a map of today's drive, say.
  fs::create_directories(path("maps"));
  fs::create_symlink("maps/today.db", path("current.db"));
  fs::create_symlink(path("current.db"), path("current_of_current.db"));
  const CommandResult built = run(build(path("current_of_current.db")));
  ASSERT_EQ(built.status, 0) << built.err;
  EXPECT_TRUE(fs::is_symlink(path("current.db")));
  EXPECT_TRUE(fs::is_symlink(path("current_of_current.db")));
  EXPECT_EQ(framesIn(path("maps/today.db")), 150);
  // A link to a pipe (or a device): the finished map would replace it.
  ASSERT_EQ(::mkfifo(path("pipe").c_str(), 0600), 0);
  fs::create_symlink(path("pipe"), path("to_pipe.db"));
  const CommandResult pipe = run(build(path("to_pipe.db"), " --force"));
  EXPECT_EQ(pipe.status, 1);
  EXPECT_NE(pipe.err.find("--output '" + path("pipe") + "' is no regular file (a device, a pipe or a socket)"),
            std::string::npos)
      << pipe.err;
  EXPECT_TRUE(fs::is_fifo(path("pipe")));
  // A loop of links leads to no file, and says so.
  fs::create_symlink(path("loop_b.db"), path("loop_a.db"));
  fs::create_symlink(path("loop_a.db"), path("loop_b.db"));
  const CommandResult loop = run(build(path("loop_a.db")));
  EXPECT_EQ(loop.status, 1);
  EXPECT_NE(loop.err.find("--output '" + path("loop_a.db") + "' is a link that leads to no file (a loop of links"),
            std::string::npos)
      << loop.err;
}

TEST_F(BuildMapTest, FilesOfTheFolderThatAreNoImagesAreNamedAsLeftOut) {
  // A ground truth beside the frames is expected; an image of an extension not known would be a
  // frame missing without a word.
  const std::string folder = path("mixed");
  fs::create_directories(folder + "/subfolder");
  for (int i = 0; i < 12; ++i) {
    const std::string name = (i < 10 ? "/0000" : "/000") + std::to_string(i) + ".png";
    fs::copy_file(path("reference") + name, folder + name);
  }
  std::ofstream(folder + "/truth.csv") << "query_index,matching_ref_indices\n";
  std::ofstream(folder + "/00012.exr") << "not read\n";
  const CommandResult built = run(buildMap() + " --images " + folder + " --output " + path("mixed.db"));
  ASSERT_EQ(built.status, 0) << built.err;
  EXPECT_NE(built.err.find("left out 2 files of '" + folder + "' not named as an image (00012.exr, truth.csv)"),
            std::string::npos)
      << built.err;
  EXPECT_EQ(framesIn(path("mixed.db")), 12);
  const CommandResult plain = run(build(path("plain.db")));
  ASSERT_EQ(plain.status, 0) << plain.err;
  EXPECT_EQ(plain.err.find("left out"), std::string::npos) << plain.err;
}

TEST_F(BuildMapTest, FramesAppendedToAMapWithoutFrameNumbersAreNumberedOnFromItsSize) {
  // As Python numbers the frames it offers to such a map (one saved before frames were numbered):
  // not from 0, which the map's own first frames stand for.
  const std::string map = path("unnumbered.db");
  {
    std::vector<mrs_vpr::StoredFrame> unnumbered = frames(7);
    for (mrs_vpr::StoredFrame& frame : unnumbered) frame.sequence = -1;
    MapDatabase(map, thumbnail()).append(unnumbered);
  }
  const CommandResult appended = run(build(map, " --append"));
  ASSERT_EQ(appended.status, 0) << appended.err;
  std::vector<std::int64_t> numbers;
  MapDatabase(map, MapAccess::kReadOnly).forEachFrame([&](const mrs_vpr::StoredFrame& frame) {
    numbers.push_back(frame.sequence);
  });
  ASSERT_GT(numbers.size(), 8U);
  EXPECT_EQ(numbers[6], -1);
  EXPECT_EQ(numbers[7], 7);
}

TEST_F(BuildMapTest, MistakesOnTheCommandLineAreRefusedBeforeAnyWork) {
  // A mistyped map name with --append would have become a second map, the map meant left as it was.
  const CommandResult append = run(build(path("no_such_map.db"), " --append"));
  EXPECT_EQ(append.status, 1);
  EXPECT_NE(append.err.find("--append: there is no map '" + path("no_such_map.db") + "' to extend"), std::string::npos)
      << append.err;
  EXPECT_FALSE(fs::exists(path("no_such_map.db")));
  const CommandResult topic = run(build(path("topic.db"), " --topic /camera/image_raw"));
  EXPECT_EQ(topic.status, 1);
  EXPECT_NE(topic.err.find("--topic is for --bag: an image folder has no topic"), std::string::npos) << topic.err;
  EXPECT_FALSE(fs::exists(path("topic.db")));
}

}  // namespace
