// images_to_bag, build_map and query_bag run as a user runs them on a generated route: the bags and
// maps they write, the evaluator reading bags, keyframes by appearance and by travel, and one-line
// errors with exit code 1 on bad input that leave no partial output.

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <rosbag/bag.h>
#include <sensor_msgs/CompressedImage.h>
#include <sensor_msgs/Image.h>

#include "mrs_vpr/evaluation/image_folder.hpp"
#include "mrs_vpr/node/bag_images.hpp"
#include "mrs_vpr/parameters.hpp"
#include "mrs_vpr/stamp.hpp"
#include "mrs_vpr/store/map_database.hpp"
#include "mrs_vpr/synthetic_route.hpp"
#include "route_tools_fixture.hpp"
#include "support/travel_bag.hpp"

/// A message filed in a bag as a sensor_msgs/Image but holding only `bytes`: a corrupt recording.
struct CorruptImage {
  std::vector<std::uint8_t> bytes;
};

namespace ros {
namespace message_traits {
template <>
struct MD5Sum<CorruptImage> {
  static const char* value() { return MD5Sum<sensor_msgs::Image>::value(); }
  static const char* value(const CorruptImage&) { return value(); }
};
template <>
struct DataType<CorruptImage> {
  static const char* value() { return DataType<sensor_msgs::Image>::value(); }
  static const char* value(const CorruptImage&) { return value(); }
};
template <>
struct Definition<CorruptImage> {
  static const char* value() { return Definition<sensor_msgs::Image>::value(); }
  static const char* value(const CorruptImage&) { return value(); }
};
}  // namespace message_traits
namespace serialization {
template <>
struct Serializer<CorruptImage> {
  template <typename Stream>
  static void write(Stream& stream, const CorruptImage& message) {
    for (const std::uint8_t byte : message.bytes) stream.next(byte);
  }
  template <typename Stream>
  static void read(Stream&, CorruptImage&) {}
  static std::uint32_t serializedLength(const CorruptImage& message) {
    return static_cast<std::uint32_t>(message.bytes.size());
  }
};
}  // namespace serialization
}  // namespace ros

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

/// An evaluation's summary without its times, which differ between runs of the same figures.
json figuresOf(const json& document) {
  json figures = document.at("summary");
  figures.erase("median_time_ms");
  figures.erase("total_time_s");
  return figures;
}

using mrs_vpr::testing_support::CommandResult;
using mrs_vpr::testing_support::fileContents;

class BagToolsTest : public mrs_vpr::testing_support::RouteToolsTest {};

TEST_F(BagToolsTest, ImagesToBagWritesIncreasingStampsAndTheEvaluatorReadsBags) {
  for (const char* traversal : {"reference", "query"}) {
    const CommandResult result =
        run(std::string(IMAGES_TO_BAG_PATH) + " --images " + path(traversal) + " --bag " +
            path(std::string(traversal) + ".bag") + " --topic /camera/image_raw --rate 10 --start-time 1000");
    ASSERT_EQ(result.status, 0) << result.err;
  }
  const auto images = mrs_vpr::bag::readImages(path("query.bag"), "/camera/image_raw", 0, 100);
  ASSERT_EQ(images.size(), 100U);
  EXPECT_EQ(images[0]->encoding, "bgr8");
  EXPECT_EQ(images[0]->width, 128U);
  EXPECT_DOUBLE_EQ(images[0]->header.stamp.toSec(), 1000.0);
  for (std::size_t i = 1; i < images.size(); ++i) {
    EXPECT_GT(images[i]->header.stamp, images[i - 1]->header.stamp);
  }
  EXPECT_NEAR(images[99]->header.stamp.toSec(), 1009.9, 1e-6);
  // Numbered as in the folder: a node's map of the bag keeps these numbers, which mrs_vpr_eval's
  // ground truth refers to (all 0, every frame of such a map was frame 0).
  for (std::size_t i = 0; i < images.size(); ++i) EXPECT_EQ(images[i]->header.seq, i);

  // Same frames from bags as from folders: the same answers.
  const std::string common = " --ground-truth " + path("truth.csv") +
                             " --method seqslam --protocol per-frame --sequence-length 10 --output ";
  ASSERT_EQ(run(eval("--reference " + path("reference") + " --query " + path("query") + common +
                     path("folders.json")))
                .status,
            0);
  const CommandResult from_bags = run(eval("--reference " + path("reference.bag") + " --query " + path("query.bag") +
                                           " --topic /camera/image_raw" + common + path("bags.json")));
  ASSERT_EQ(from_bags.status, 0) << from_bags.err;
  const json folders = json::parse(fileContents(path("folders.json")));
  const json bags = json::parse(fileContents(path("bags.json")));
  ASSERT_EQ(folders["records"].size(), bags["records"].size());
  for (std::size_t i = 0; i < folders["records"].size(); ++i) {
    EXPECT_EQ(folders["records"][i]["predicted_index"], bags["records"][i]["predicted_index"]) << i;
  }

  expectError("--reference " + path("reference.bag") + " --query " + path("query.bag") +
                  " --method seqslam --protocol per-frame --sequence-length 10",
              "reading a bag needs --topic");
  expectError("--reference " + path("reference.bag") + " --query " + path("query.bag") +
                  " --topic /nothing --method seqslam --protocol per-frame --sequence-length 10",
              "has no topic '/nothing' (it has: /camera/image_raw (sensor_msgs/Image))");
}

// rosbag (with roslib, rospack and Python) is a plugin loaded on the first bag read: a run that reads
// no bag starts without it. LD_DEBUG=files makes the dynamic loader name every library it opens.
TEST_F(BagToolsTest, ACompressedBayerMosaicIsReadAsItsBayerEncoding) {
  // A Bayer camera's frames recorded through image_transport's compressed publisher: the mosaic as a
  // PNG, "bayer_rggb8; png compressed ". The tools must read it as the node does: a mosaic to demosaic,
  // not a grey image.
  cv::Mat mosaic(48, 64, CV_8UC1);
  cv::randu(mosaic, 0, 256);
  const std::string bag_path = path("bayer_compressed.bag");
  {
    rosbag::Bag writer(bag_path, rosbag::bagmode::Write);
    int second = 100;
    for (const std::string format : {"bayer_rggb8; png compressed ", "bayer_rggb8; png compressed mono8", "png"}) {
      sensor_msgs::CompressedImage compressed;
      compressed.header.stamp = ros::Time(second++, 0);
      compressed.format = format;
      cv::imencode(".png", mosaic, compressed.data);
      writer.write("/camera/image_raw/compressed", compressed.header.stamp, compressed);
    }
  }
  const auto images = mrs_vpr::bag::readImages(bag_path, "/camera/image_raw/compressed", 0, 3);
  ASSERT_EQ(images.size(), 3U);
  EXPECT_EQ(images[0]->encoding, "bayer_rggb8");
  EXPECT_EQ(images[1]->encoding, "mono8");  // made grey before it was compressed
  EXPECT_EQ(images[2]->encoding, "mono8");
  for (const auto& image : images) {
    ASSERT_EQ(image->data.size(), mosaic.total());
    EXPECT_TRUE(std::equal(image->data.begin(), image->data.end(), mosaic.data)) << image->encoding;
  }
}

TEST_F(BagToolsTest, TheEvaluatorLoadsTheBagReaderOnlyWhenItReadsABag) {
  const CommandResult help = run("LD_DEBUG=files " + eval("--help"));
  ASSERT_EQ(help.status, 0) << help.err;
  ASSERT_NE(help.err.find("libmrs_vpr_core.so"), std::string::npos) << "LD_DEBUG gave no listing";
  EXPECT_EQ(help.err.find("librosbag_storage"), std::string::npos);
  EXPECT_EQ(help.err.find("libmrs_vpr_rosbag_reader"), std::string::npos);

  const CommandResult written = run(std::string(IMAGES_TO_BAG_PATH) + " --images " + path("reference") + " --bag " +
                                    path("lazy.bag") + " --topic /camera/image_raw --rate 10");
  ASSERT_EQ(written.status, 0) << written.err;
  const std::string arguments = "--reference " + path("lazy.bag") + " --query " + path("query") +
                                " --topic /camera/image_raw --ground-truth " + path("truth.csv") +
                                " --method seqslam --protocol per-frame --sequence-length 10";
  const CommandResult from_bag = run("LD_DEBUG=files " + eval(arguments));
  ASSERT_EQ(from_bag.status, 0) << from_bag.err;
  EXPECT_NE(from_bag.err.find("libmrs_vpr_rosbag_reader.so"), std::string::npos);
  EXPECT_NE(from_bag.err.find("librosbag_storage"), std::string::npos);
}

TEST_F(BagToolsTest, ImagesToBagRejectsBadArguments) {
  const CommandResult no_rate = run(std::string(IMAGES_TO_BAG_PATH) + " --images " + path("query") + " --bag " +
                                    path("x.bag") + " --topic /t --rate 0");
  EXPECT_EQ(no_rate.status, 1);
  EXPECT_NE(no_rate.err.find("--rate must be > 0"), std::string::npos) << no_rate.err;
  // Faster than a frame a nanosecond, every frame had one stamp.
  const CommandResult too_fast = run(std::string(IMAGES_TO_BAG_PATH) + " --images " + path("query") + " --bag " +
                                     path("x.bag") + " --topic /t --rate 1e12");
  EXPECT_EQ(too_fast.status, 1);
  EXPECT_NE(too_fast.err.find("--rate must be at most 1e9 Hz, one frame a nanosecond (a stamp's resolution), got "
                              "1000000000000"),
            std::string::npos)
      << too_fast.err;
  const CommandResult no_folder = run(std::string(IMAGES_TO_BAG_PATH) + " --images " + path("nowhere") + " --bag " +
                                      path("x.bag") + " --topic /t --rate 5");
  EXPECT_EQ(no_folder.status, 1);
  EXPECT_NE(no_folder.err.find("does not exist"), std::string::npos) << no_folder.err;
  EXPECT_FALSE(fs::exists(path("x.bag")));  // Nothing written for a bad folder.
  const CommandResult no_topic = run(std::string(IMAGES_TO_BAG_PATH) + " --images " + path("query") + " --bag " +
                                     path("x.bag") + " --topic '' --rate 5");
  EXPECT_EQ(no_topic.status, 1);
  EXPECT_NE(no_topic.err.find("--topic must not be empty"), std::string::npos) << no_topic.err;
  const CommandResult no_bag =
      run(std::string(IMAGES_TO_BAG_PATH) + " --images " + path("query") + " --bag '' --topic /t --rate 5");
  EXPECT_EQ(no_bag.status, 1);
  EXPECT_NE(no_bag.err.find("--bag was given an empty path"), std::string::npos) << no_bag.err;
  const CommandResult no_images =
      run(std::string(IMAGES_TO_BAG_PATH) + " --images '' --bag " + path("x.bag") + " --topic /t --rate 5");
  EXPECT_EQ(no_images.status, 1);
  EXPECT_NE(no_images.err.find("--images was given an empty path"), std::string::npos) << no_images.err;
  const CommandResult no_bag_folder = run(std::string(IMAGES_TO_BAG_PATH) + " --images " + path("query") + " --bag " +
                                          path("nowhere/x.bag") + " --topic /t --rate 5");
  EXPECT_EQ(no_bag_folder.status, 1);
  EXPECT_NE(no_bag_folder.err.find("--bag '" + path("nowhere/x.bag") + "': there is no folder " + path("nowhere")),
            std::string::npos)
      << no_bag_folder.err;
}

TEST_F(BagToolsTest, AStoppedImagesToBagLeavesNoUnfinishedBag) {
  const std::string bag = path("stopped.bag");
  const CommandResult stopped = run(mrs_vpr::testing_support::stoppedOnceExists(
      std::string(IMAGES_TO_BAG_PATH) + " --images " + manyFrames() + " --bag " + bag + " --topic /t --rate 30",
      bag + ".part"));
  EXPECT_EQ(stopped.status, 128 + SIGTERM) << stopped.err;
  EXPECT_NE(stopped.err.find("images_to_bag: interrupted by SIGTERM"), std::string::npos) << stopped.err;
  EXPECT_FALSE(fs::exists(bag));
  EXPECT_FALSE(fs::exists(bag + ".part"));
}

TEST_F(BagToolsTest, ByDefaultBuildMapAndTheEvaluatorKeepOnlyFramesWhoseViewChanged) {
  // The reference route with a stop: frame 60 shown 40 times more, each time with sensor noise.
  const mrs_vpr::SyntheticRoute& route = mrs_vpr::testing_support::routeOfFolders();
  std::vector<cv::Mat> stopped;
  cv::RNG rng(9);
  for (int i = 0; i < static_cast<int>(route.reference.size()); ++i) {
    stopped.push_back(route.reference[static_cast<std::size_t>(i)]);
    for (int repeat = 0; i == 60 && repeat < 40; ++repeat) {
      cv::Mat noise(route.reference[60].size(), CV_16SC3);
      rng.fill(noise, cv::RNG::NORMAL, 0, 2);
      cv::Mat noisy;
      cv::add(route.reference[60], noise, noisy, cv::noArray(), CV_8UC3);
      stopped.push_back(noisy);
    }
  }
  mrs_vpr::testing_support::writeImageFolder(path("stopped"), stopped);
  const CommandResult built =
      run(std::string(BUILD_MAP_PATH) + " --images " + path("stopped") + " --output " + path("stopped.db"));
  ASSERT_EQ(built.status, 0) << built.err;
  // Every stopped frame is too similar to the frame the robot stopped at; of the moving ones, a few.
  const std::size_t too_similar = built.err.find(" frames too similar");
  ASSERT_NE(too_similar, std::string::npos) << built.err;
  const int skipped = std::stoi(built.err.substr(built.err.rfind(' ', too_similar - 1) + 1));
  EXPECT_GE(skipped, 40) << built.err;
  EXPECT_LT(skipped, 40 + 20) << built.err;

  // The evaluator keeps the same keyframes of the reference, and names frames in its records.
  const std::string output = path("stopped.json");
  const CommandResult evaluated = run(std::string(MRS_VPR_EVAL_PATH) + " --reference " + path("stopped") + " --query " +
                                      path("query") + " --protocol per-frame --sequence-length 10 --output " + output);
  ASSERT_EQ(evaluated.status, 0) << evaluated.err;
  const json document = json::parse(fileContents(output));
  EXPECT_EQ(document.at("reference_frames"), 190);
  EXPECT_EQ(document.at("reference_keyframes"), 190 - skipped);
  EXPECT_EQ(document.at("parameters").at("min_appearance_change"), mrs_vpr::RecognizerParams{}.min_appearance_change);
  EXPECT_EQ(document.at("parameters").at("method"), mrs_vpr::RecognizerParams{}.default_method);
  for (const json& record : document.at("records")) {
    EXPECT_GE(record.at("predicted_last").get<int>(), record.at("predicted_index").get<int>());
  }
  // One keyframe stands for the stop: of folder frames 60 (where the robot stopped) to 100, the map
  // keeps one, and build_map numbers it by its frame in the folder.
  int stop_keyframes = 0;
  mrs_vpr::MapDatabase(path("stopped.db"), mrs_vpr::MapAccess::kReadOnly)
      .forEachFrame([&](const mrs_vpr::StoredFrame& frame) {
        if (frame.sequence >= 60 && frame.sequence <= 100) ++stop_keyframes;
      });
  EXPECT_EQ(stop_keyframes, 1);

  // The map keeps each keyframe's index in the folder, so that the evaluator judges it by the folder's
  // frames and gives the folder's figures.
  const std::string rest = " --query " + path("query") + " --protocol per-frame --sequence-length 10";
  const CommandResult from_map = run(std::string(MRS_VPR_EVAL_PATH) + " --reference " + path("stopped.db") + rest);
  ASSERT_EQ(from_map.status, 0) << from_map.err;
  EXPECT_NE(from_map.err.find("frames 0 to 189 of its traversal of 190 frames by the numbers it stores"),
            std::string::npos)
      << from_map.err;
  EXPECT_EQ(figuresOf(json::parse(from_map.out)), figuresOf(document));
  // The plots draw every frame of the reference, which the map does not hold.
  const CommandResult plots = run(std::string(MRS_VPR_EVAL_PATH) + " --reference " + path("stopped.db") + rest +
                                  " --plots " + path("stopped_plots"));
  EXPECT_EQ(plots.status, 1);
  EXPECT_NE(plots.err.find("holds " + std::to_string(190 - skipped) + " of 190: give its image folder or bag instead"),
            std::string::npos)
      << plots.err;
}

TEST_F(BagToolsTest, AMapWhoseLastFramesWereNotKeptIsJudgedOnEveryFrameOfItsTraversal) {
  // A traversal that ends standing still (the corridor set's does): its last frames are too similar to
  // be kept, and a ground truth may name them. The map records the traversal's length, so that the
  // map is judged as its folder is.
  const std::string folder = path("ends_standing");
  fs::create_directories(folder);
  const std::vector<std::string> images = mrs_vpr::listImageFiles(path("reference"));
  for (std::size_t i = 0; i < images.size() + 5; ++i) {
    fs::create_symlink(images[std::min(i, images.size() - 1)], folder + "/" + std::to_string(10000 + i) + ".png");
  }
  {
    std::ifstream truth(path("truth.csv"));
    std::ofstream named(path("names_the_last_frames.csv"));
    std::string line;
    while (std::getline(truth, line)) named << line << (line.rfind("99,", 0) == 0 ? " 154" : "") << "\n";
  }
  const std::string map = path("ends_standing.db");
  const CommandResult built = run(std::string(BUILD_MAP_PATH) + " --descriptor thumbnail --images " + folder +
                                  " --output " + map);
  ASSERT_EQ(built.status, 0) << built.err;
  const std::string rest = " --descriptor thumbnail --query " + path("query") + " --ground-truth " +
                           path("names_the_last_frames.csv") + " --protocol per-frame --sequence-length 10";
  const CommandResult from_folder = run(std::string(MRS_VPR_EVAL_PATH) + " --reference " + folder + rest);
  const CommandResult from_map = run(std::string(MRS_VPR_EVAL_PATH) + " --reference " + map + rest);
  ASSERT_EQ(from_folder.status, 0) << from_folder.err;
  ASSERT_EQ(from_map.status, 0) << from_map.err;
  EXPECT_NE(from_map.err.find("of its traversal of 155 frames by the numbers it stores"), std::string::npos)
      << from_map.err;
  EXPECT_EQ(figuresOf(json::parse(from_map.out)), figuresOf(json::parse(from_folder.out)));
  // Without --min-appearance-change the query is keyframed as the map's frames were; with another
  // value, the evaluator warns.
  const std::string at_03 = path("kept_at_0.3.db");
  ASSERT_EQ(run(std::string(BUILD_MAP_PATH) + " --descriptor thumbnail --min-appearance-change 0.3 --images " + folder +
                " --output " + at_03)
                .status,
            0);
  const CommandResult map_keyframing = run(std::string(MRS_VPR_EVAL_PATH) + " --reference " + at_03 + rest +
                                           " --output " + path("kept_at_0.3.json"));
  ASSERT_EQ(map_keyframing.status, 0) << map_keyframing.err;
  EXPECT_NE(map_keyframing.err.find("keyframes at an appearance change of 0.3"), std::string::npos)
      << map_keyframing.err;
  EXPECT_EQ(nlohmann::json::parse(fileContents(path("kept_at_0.3.json"))).at("parameters").at("min_appearance_change"),
            0.3);
  EXPECT_EQ(map_keyframing.err.find("warning"), std::string::npos) << map_keyframing.err;
  const CommandResult other = run(std::string(MRS_VPR_EVAL_PATH) + " --reference " + at_03 + rest +
                                  " --min-appearance-change 0");
  ASSERT_EQ(other.status, 0) << other.err;
  EXPECT_NE(other.err.find("warning: the map's keyframes were kept at an appearance change of 0.3, and "
                           "--min-appearance-change is 0"),
            std::string::npos)
      << other.err;
  // Extended by build_map: numbered on after the traversal the map records (not after its last
  // keyframe, which would give the first traversal's last frames' numbers again), at the map's own
  // appearance change; at another, it says so and the map records none.
  const std::int64_t kept_before = mrs_vpr::MapDatabase(at_03, mrs_vpr::MapAccess::kReadOnly).size();
  const std::string append = std::string(BUILD_MAP_PATH) + " --images " + path("query") + " --output " + at_03 +
                             " --append";
  const CommandResult appended = run(append);
  ASSERT_EQ(appended.status, 0) << appended.err;
  EXPECT_NE(appended.err.find("(--min-appearance-change 0.3)"), std::string::npos) << appended.err;
  {
    const mrs_vpr::MapDatabase extended(at_03, mrs_vpr::MapAccess::kReadOnly);
    ASSERT_TRUE(extended.traversal().has_value());
    EXPECT_EQ(extended.traversal()->frames, 155 + 100);
    EXPECT_EQ(extended.traversal()->min_appearance_change, 0.3);
    std::int64_t index = 0;
    extended.forEachFrame([&](const mrs_vpr::StoredFrame& frame) {
      if (index++ >= kept_before) EXPECT_GE(frame.sequence, 155);
    });
  }
  const CommandResult mixed = run(append + " --min-appearance-change 0");
  ASSERT_EQ(mixed.status, 0) << mixed.err;
  EXPECT_NE(mixed.err.find("build_map: warning: the map's keyframes were kept at an appearance change of 0.3, and "
                           "--min-appearance-change is 0"),
            std::string::npos)
      << mixed.err;
  ASSERT_TRUE(mrs_vpr::MapDatabase(at_03, mrs_vpr::MapAccess::kReadOnly).traversal().has_value());
  EXPECT_FALSE(mrs_vpr::MapDatabase(at_03, mrs_vpr::MapAccess::kReadOnly).traversal()->min_appearance_change);

  // Extended by the node or another traversal, the map is no longer that traversal alone.
  {
    mrs_vpr::MapDatabase database(map, mrs_vpr::MapAccess::kReadWrite);
    ASSERT_TRUE(database.traversal().has_value());
    EXPECT_EQ(database.traversal()->frames, 155);
    EXPECT_EQ(database.traversal()->min_appearance_change, mrs_vpr::RecognizerParams{}.min_appearance_change);
    const int bytes = static_cast<int>(database.descriptorParams().descriptorSize());
    database.append({{cv::Mat(1, bytes, CV_8U, cv::Scalar(7)), mrs_vpr::Stamp(), "", 155}});
    EXPECT_FALSE(database.traversal().has_value());
  }
  EXPECT_FALSE(mrs_vpr::MapDatabase(map, mrs_vpr::MapAccess::kReadOnly).traversal().has_value());
}

TEST_F(BagToolsTest, AMapBuiltOfAFolderAnswersAsTheFolderDoes) {
  const std::string map = path("reference.db");
  const std::string build = buildMap() + " --images " + path("reference") + " --output " + map;
  const CommandResult built = run(build);
  ASSERT_EQ(built.status, 0) << built.err;
  EXPECT_NE(built.err.find("150 frames added to 0"), std::string::npos) << built.err;
  EXPECT_FALSE(fs::exists(map + ".part"));

  const std::string rest = " --query " + path("query") + " --ground-truth " + path("truth.csv") +
                           " --method seqslam --protocol per-frame --sequence-length 10 --tolerance 2";
  const CommandResult from_folder = run(eval("--reference " + path("reference") + rest));
  const CommandResult from_map = run(eval("--reference " + map + rest));
  ASSERT_EQ(from_folder.status, 0) << from_folder.err;
  ASSERT_EQ(from_map.status, 0) << from_map.err;
  EXPECT_EQ(figuresOf(json::parse(from_map.out)), figuresOf(json::parse(from_folder.out)));
  // A ground truth of another traversal is refused once the map is read, before the query is described.
  {
    std::ofstream beyond(path("beyond.csv"));
    beyond << "query_index,matching_ref_indices\n0,0\n1,150\n";
  }
  const CommandResult beyond = run(eval("--reference " + map + " --query " + path("query") + " --ground-truth " +
                                        path("beyond.csv") + " --method seqslam --protocol per-frame"));
  EXPECT_EQ(beyond.status, 1);
  EXPECT_NE(beyond.err.find("query frame 1 lists reference frame 150, but the reference has 150 frames"),
            std::string::npos)
      << beyond.err;
  EXPECT_EQ(beyond.err.find("query:"), std::string::npos) << beyond.err;

  // An existing map is neither replaced nor extended unless asked.
  const CommandResult again = run(build);
  EXPECT_EQ(again.status, 1);
  EXPECT_NE(again.err.find("exists; use --append to extend it or --force to replace it"), std::string::npos);
  fs::permissions(map, fs::perms::owner_read | fs::perms::owner_write);  // A private map...
  const CommandResult appended = run(build + " --append");
  EXPECT_EQ(appended.status, 0) << appended.err;
  EXPECT_NE(appended.err.find("150 frames added to 150"), std::string::npos) << appended.err;
  // ... stays private, and the appended folder's frames go on from its numbers and stamps (frame i at
  // i s), so that no two frames share a stamp.
  EXPECT_EQ(fs::status(map).permissions(), fs::perms::owner_read | fs::perms::owner_write);
  std::int64_t frame = 0;
  mrs_vpr::MapDatabase(map, mrs_vpr::MapAccess::kReadOnly).forEachFrame([&](const mrs_vpr::StoredFrame& stored) {
    EXPECT_EQ(stored.sequence, frame);
    EXPECT_EQ(stored.stamp, mrs_vpr::Stamp::fromSecondsAndNanoseconds(static_cast<std::uint32_t>(frame), 0));
    ++frame;
  });
  EXPECT_EQ(frame, 300);

  // An extension that fails after a first batch of 1000 frames leaves the map as it was (it kept that
  // batch before, and a second run after the image was mended would have stored it twice).
  fs::create_directories(path("long"));
  std::vector<fs::path> images;
  for (const auto& entry : fs::directory_iterator(path("reference"))) images.push_back(entry.path());
  for (std::size_t i = 0; i < 1050; ++i) {
    fs::create_symlink(images[i % images.size()], fs::path(path("long")) / (std::to_string(10000 + i) + ".png"));
  }
  std::ofstream(path("long/99999.png")) << "not an image";
  const CommandResult failed = run(buildMap() + " --images " + path("long") + " --output " + map + " --append");
  EXPECT_EQ(failed.status, 1) << failed.err;
  EXPECT_NE(failed.err.find("99999.png"), std::string::npos) << failed.err;
  EXPECT_EQ(mrs_vpr::MapDatabase(map, mrs_vpr::MapAccess::kReadOnly).size(), 300);
  EXPECT_FALSE(fs::exists(map + ".part"));
}

TEST_F(BagToolsTest, AMapNumberedFromLaterOnHoldsNoPlaceBeforeItsFirstFrame) {
  // A map whose frames are numbered from 40 on (a node's map, numbered by header.seq): by the identity
  // ground truth, query frames 0 to 39 show places outside it, not places it should have answered.
  ASSERT_EQ(run(buildMap() + " --images " + path("reference") + " --output " + path("numbered.db")).status, 0);
  std::vector<mrs_vpr::StoredFrame> late;
  mrs_vpr::DescriptorParams params;
  {
    const mrs_vpr::MapDatabase numbered(path("numbered.db"), mrs_vpr::MapAccess::kReadOnly);
    params = numbered.descriptorParams();
    numbered.forEachFrame([&](const mrs_vpr::StoredFrame& frame) {
      if (frame.sequence >= 40) late.push_back({frame.descriptor.clone(), frame.stamp, frame.frame_id, frame.sequence});
    });
  }
  ASSERT_EQ(late.size(), 110U);
  { mrs_vpr::MapDatabase(path("late.db"), params).append(late); }

  const CommandResult result =
      run(eval("--reference " + path("late.db") + " --query " + path("query") +
               " --method seqslam --protocol per-frame --sequence-length 10 --output " + path("late.json")));
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_NE(result.err.find("query frames 0 to 39 show, by the identity ground truth, places before the map's first"),
            std::string::npos)
      << result.err;
  int before_the_map = 0;
  const json document = json::parse(fileContents(path("late.json")));
  for (const json& record : document.at("records")) {
    const int frame = record.at("query_index").get<int>();
    EXPECT_EQ(record.at("true_indices").empty(), frame < 40) << "query frame " << frame;
    before_the_map += frame < 40 ? 1 : 0;
  }
  EXPECT_GT(before_the_map, 0);
}

TEST_F(BagToolsTest, AMapIsReadAndExtendedWithTheFrontEndItRecords) {
  // Without a front-end option the evaluator and build_map --append take the map's own front end;
  // another one named is refused, naming the file and both front ends.
  const std::string build_map = std::string(BUILD_MAP_PATH) + " --images " + path("reference") + " --output " +
                                path("small.db");
  const CommandResult other = run(build_map + " --descriptor thumbnail --image-width 32 --image-height 16");
  ASSERT_EQ(other.status, 0) << other.err;
  const std::string evaluate = std::string(MRS_VPR_EVAL_PATH) + " --reference " + path("small.db") + " --query " +
                               path("query") + " --ground-truth " + path("truth.csv") +
                               " --protocol per-frame --sequence-length 10";
  const CommandResult adopted = run(evaluate + " --output " + path("small.json"));
  ASSERT_EQ(adopted.status, 0) << adopted.err;
  EXPECT_NE(adopted.err.find("thumbnail (32 x 16, patches of 8 px)"), std::string::npos) << adopted.err;
  const json parameters = json::parse(fileContents(path("small.json"))).at("parameters").at("descriptor");
  EXPECT_EQ(parameters.at("type"), "thumbnail");
  EXPECT_EQ(parameters.at("image_width"), 32);
  const CommandResult refused = run(evaluate + " --descriptor hog");
  EXPECT_EQ(refused.status, 1);
  EXPECT_NE(refused.err.find(path("small.db")), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("holds descriptors of the thumbnail (32 x 16, patches of 8 px) front end, not of the "
                             "hog (128 x 64 window"),
            std::string::npos)
      << refused.err;
  const CommandResult appended = run(build_map + " --append");
  EXPECT_EQ(appended.status, 0) << appended.err;
  const CommandResult mixed = run(build_map + " --append --descriptor hog");
  EXPECT_EQ(mixed.status, 1);
  EXPECT_NE(mixed.err.find("not of the hog"), std::string::npos) << mixed.err;
}

TEST_F(BagToolsTest, AMapBuiltOfABagWithMinTravelHasAFrameEachMetre) {
  // The robot drives 4 m, stands still for 30 frames and drives 2 m on (support/travel_bag.hpp).
  const std::string bag = path("drive.bag");
  mrs_vpr::testing_support::writeTravelBag(bag, "/camera/image_raw", mrs_vpr::testing_support::driveStopDrive());
  const std::string build = buildMap() + " --bag " + bag + " --topic /camera/image_raw --output ";
  const CommandResult every_frame = run(build + path("every_frame.db"));
  ASSERT_EQ(every_frame.status, 0) << every_frame.err;
  EXPECT_NE(every_frame.err.find("51 frames added to 0"), std::string::npos) << every_frame.err;

  const CommandResult by_travel = run(build + path("by_travel.db") + " --min-travel 1");
  ASSERT_EQ(by_travel.status, 0) << by_travel.err;
  EXPECT_NE(by_travel.err.find("7 frames added to 0"), std::string::npos) << by_travel.err;
  EXPECT_NE(by_travel.err.find("7 keyframes of 51 frames at min_travel 1 m (44 too near, 0 without a pose"),
            std::string::npos)
      << by_travel.err;
  // A map kept by travel records its frames, and no appearance change; one kept by appearance change
  // and extended by travel says so, and records none any more.
  const std::optional<mrs_vpr::MapTraversal> travel =
      mrs_vpr::MapDatabase(path("by_travel.db"), mrs_vpr::MapAccess::kReadOnly).traversal();
  ASSERT_TRUE(travel.has_value());
  EXPECT_EQ(travel->frames, 51);
  EXPECT_FALSE(travel->min_appearance_change.has_value());
  const CommandResult mixed = run(build + path("every_frame.db") + " --append --min-travel 1");
  ASSERT_EQ(mixed.status, 0) << mixed.err;
  EXPECT_NE(mixed.err.find("build_map: warning: the map's keyframes were kept at an appearance change of 0, and these "
                           "by travel (--min-travel)"),
            std::string::npos)
      << mixed.err;
  EXPECT_FALSE(mrs_vpr::MapDatabase(path("every_frame.db"), mrs_vpr::MapAccess::kReadOnly)
                   .traversal()
                   ->min_appearance_change.has_value());

  // Frames tf has no pose for are skipped, and the user is told why; when that is every frame (a frame
  // name tf does not know), there is no map, not an empty one.
  const CommandResult unknown_frame = run(build + path("gripper.db") + " --min-travel 1 --base-frame gripper");
  EXPECT_EQ(unknown_frame.status, 1) << unknown_frame.err;
  EXPECT_NE(unknown_frame.err.find("no frame was kept: 0 keyframes of 51 frames at min_travel 1 m (0 too near, 51 "
                                   "without a pose of 'gripper'"),
            std::string::npos)
      << unknown_frame.err;
  EXPECT_NE(unknown_frame.err.find("the first frame without a pose: "), std::string::npos) << unknown_frame.err;
  EXPECT_FALSE(fs::exists(path("gripper.db")));
  EXPECT_FALSE(fs::exists(path("gripper.db.part")));
}

TEST_F(BagToolsTest, MinTravelWithoutPosesIsRefusedAndWritesNothing) {
  const std::string no_poses = path("no_poses.bag");
  mrs_vpr::testing_support::writeTravelBag(no_poses, "/camera/image_raw", mrs_vpr::testing_support::driveStopDrive(),
                                           false);
  const CommandResult without_tf = run(buildMap() + " --bag " + no_poses +
                                       " --topic /camera/image_raw --min-travel 1 --output " + path("no_poses.db"));
  EXPECT_EQ(without_tf.status, 1);
  EXPECT_NE(without_tf.err.find("has no /tf or /tf_static messages"), std::string::npos) << without_tf.err;
  EXPECT_FALSE(fs::exists(path("no_poses.db")));
  EXPECT_FALSE(fs::exists(path("no_poses.db.part")));

  const CommandResult folder =
      run(buildMap() + " --images " + path("reference") + " --min-travel 1" + " --output " + path("folder.db"));
  EXPECT_EQ(folder.status, 1);
  EXPECT_NE(folder.err.find("--min-travel needs --bag"), std::string::npos) << folder.err;
  const CommandResult negative = run(buildMap() + " --bag " + no_poses +
                                     " --topic /camera/image_raw --min-travel=-1 --output " + path("negative.db"));
  EXPECT_EQ(negative.status, 1);
  EXPECT_NE(negative.err.find("min_travel must be a finite number of metres >= 0"), std::string::npos) << negative.err;
  const CommandResult recent = run(std::string(QUERY_BAG_PATH) + " --recent-frames 10 --min-travel 1");
  EXPECT_EQ(recent.status, 1);
  EXPECT_NE(recent.err.find("--min-travel needs --bag, not --recent-frames"), std::string::npos) << recent.err;
  const CommandResult method = run(std::string(QUERY_BAG_PATH) + " --recent-frames 10 --method fastest");
  EXPECT_EQ(method.status, 1);
  EXPECT_NE(method.err.find("--method must be mrs or seqslam, got 'fastest'"), std::string::npos) << method.err;
  // Checked before the service is asked: a sequence of one frame is no sequence.
  const CommandResult one = run(std::string(QUERY_BAG_PATH) + " --recent-frames 1 --service /nope/query");
  EXPECT_EQ(one.status, 1);
  EXPECT_NE(one.err.find("--recent-frames must be >= 2"), std::string::npos) << one.err;
  const CommandResult no_topic = run(std::string(QUERY_BAG_PATH) + " --bag /nope.bag --topic '' --count 5");
  EXPECT_EQ(no_topic.status, 1);
  EXPECT_NE(no_topic.err.find("--topic is empty: name the image topic of the bag"), std::string::npos) << no_topic.err;
  const CommandResult one_image = run(std::string(QUERY_BAG_PATH) + " --bag /nope.bag --topic /t --count 1");
  EXPECT_EQ(one_image.status, 1);
  EXPECT_NE(one_image.err.find("--count must be >= 2, as ~query takes it"), std::string::npos) << one_image.err;
  // Where the node's own setting is the default, --help says so rather than the core's value.
  const CommandResult help = run(std::string(QUERY_BAG_PATH) + " --help");
  EXPECT_NE(help.out.find("--min-appearance-change arg (=the node's)"), std::string::npos) << help.out;
  EXPECT_NE(help.out.find("--descriptor arg (=the node's)"), std::string::npos) << help.out;
}

TEST_F(BagToolsTest, QueryBagWithoutAMasterSaysSo) {
  // The master, not the node, is what is missing: the message says so.
  const CommandResult result = run("ROS_MASTER_URI=http://localhost:9 " + std::string(QUERY_BAG_PATH) +
                                   " --recent-frames 10 --timeout 0.5");
  EXPECT_EQ(result.status, 1);
  EXPECT_NE(result.err.find("query_bag: error: service /mrs_vpr/query is not available after 0.5 s: no ROS master "
                            "answers at ROS_MASTER_URI=http://localhost:9 (is roscore running?)"),
            std::string::npos)
      << result.err;
  // A stop while it waits ends the wait at once: an interruption, not a timeout of 30 s after 1, nor
  // a wait of all 30. (SIGTERM: a shell that is not interactive starts a background job with SIGINT
  // ignored, as is this test when its runner was, and no shell may undo that; Ctrl-C takes the same
  // path, catchInterruptions.)
  const auto began = std::chrono::steady_clock::now();
  const CommandResult stopped =
      run("{ ROS_MASTER_URI=http://localhost:9 " + std::string(QUERY_BAG_PATH) +
          " --recent-frames 10 --timeout 30 & pid=$!; sleep 1; kill -TERM $pid; wait $pid; }");
  EXPECT_EQ(stopped.status, 128 + SIGTERM) << stopped.err;
  EXPECT_NE(stopped.err.find("query_bag: interrupted by SIGTERM"), std::string::npos) << stopped.err;
  EXPECT_LT(std::chrono::steady_clock::now() - began, std::chrono::seconds(15));
}

TEST_F(BagToolsTest, QueryBagRefusesATimeoutThatWouldWaitForEver) {
  // No master is needed: the options are checked first. -1 used to wait for the service for ever.
  for (const char* timeout : {"-1", "0", "1e9"}) {
    const CommandResult result =
        run(std::string(QUERY_BAG_PATH) + " --recent-frames 10 --service /nope/query --timeout " + timeout);
    EXPECT_EQ(result.status, 1) << timeout;
    EXPECT_NE(result.err.find("--timeout must be in (0, 3600] s"), std::string::npos) << result.err;
    EXPECT_TRUE(result.out.empty()) << "stdout holds only the JSON answer: " << result.out;
  }
  // A service that no node can offer is named as such, not waited for.
  const CommandResult unnamed = run(std::string(QUERY_BAG_PATH) + " --recent-frames 10 --service ''");
  EXPECT_EQ(unnamed.status, 1);
  EXPECT_NE(unnamed.err.find("--service must not be empty"), std::string::npos) << unnamed.err;
  const CommandResult no_bag = run(std::string(QUERY_BAG_PATH) + " --bag '' --topic /t --count 5");
  EXPECT_EQ(no_bag.status, 1);
  EXPECT_NE(no_bag.err.find("--bag was given an empty path"), std::string::npos) << no_bag.err;
  const CommandResult invalid = run(std::string(QUERY_BAG_PATH) + " --recent-frames 10 --service 'my query'");
  EXPECT_EQ(invalid.status, 1);
  EXPECT_NE(invalid.err.find("--service 'my query' is not a valid ROS name"), std::string::npos) << invalid.err;
}

TEST_F(BagToolsTest, MakeDemoRouteChecksItsOptionsFirstAndWritesWholeBagsOnly) {
  const std::string tool = std::string(MAKE_DEMO_ROUTE_PATH) + " --output " + path("demo");
  for (const auto& [options, problem] :
       std::vector<std::pair<std::string, std::string>>{{" --rate inf", "--rate must be > 0 Hz"},
                                                        // Every frame would have one stamp.
                                                        {" --rate 1e12", "--rate must be at most 1e9 Hz, one frame"},
                                                        {" --seed -1", "--seed must be >= 0, got -1"},
                                                        {" --topic 'bad topic'", "is not a valid ROS topic name"},
                                                        // The query traversal, an hour later, would not fit.
                                                        {" --start-time 4294966000", "cannot all be stamped"},
                                                        // Counts before stamps, which would name frame -1.
                                                        {" --query-frames 0", "needs 2..1000000 reference frames"},
                                                        {" --reference-frames -5", "needs 2..1000000 reference"}}) {
    const CommandResult refused = run(tool + options);
    EXPECT_EQ(refused.status, 1) << options;
    EXPECT_NE(refused.err.find(problem), std::string::npos) << refused.err;
    EXPECT_FALSE(fs::exists(path("demo/reference.bag"))) << options;  // Before, a partial bag was left.
  }
  const CommandResult written = run(tool + " --reference-frames 30 --query-frames 20");
  ASSERT_EQ(written.status, 0) << written.err;
  for (const char* file : {"reference.bag", "query.bag", "ground_truth.csv"}) {
    EXPECT_TRUE(fs::exists(path("demo/") + file)) << file;
    EXPECT_FALSE(fs::exists(path("demo/") + file + ".part")) << file;
  }
  // An earlier route is replaced only with --force.
  const std::string first_route = fileContents(path("demo/reference.bag"));
  const CommandResult again = run(tool + " --reference-frames 40 --query-frames 20");
  EXPECT_EQ(again.status, 1);
  EXPECT_NE(again.err.find("'" + path("demo/reference.bag") + "' exists: use --force"), std::string::npos)
      << again.err;
  EXPECT_EQ(fileContents(path("demo/reference.bag")), first_route);
  ASSERT_EQ(run(tool + " --reference-frames 40 --query-frames 20 --force").status, 0);
  EXPECT_NE(fileContents(path("demo/reference.bag")), first_route);
  // Folders of frames are replaced whole: a shorter route leaves none of the longer one's frames.
  ASSERT_EQ(run(tool + " --reference-frames 40 --query-frames 20 --force --images").status, 0);
  ASSERT_EQ(run(tool + " --reference-frames 30 --query-frames 10 --force --images").status, 0);
  const auto count = [&](const char* folder) {
    return std::distance(fs::directory_iterator(path("demo/") + folder), fs::directory_iterator{});
  };
  EXPECT_EQ(count("reference"), 30);
  EXPECT_EQ(count("query"), 10);
  // And without --images, an earlier route's folders go with it.
  ASSERT_EQ(run(tool + " --reference-frames 30 --query-frames 10 --force").status, 0);
  EXPECT_FALSE(fs::exists(path("demo/reference")));
  // A folder of other files is not the tool's to remove, and nothing is removed when one is found:
  // not the other folder's frames either.
  ASSERT_EQ(run(tool + " --reference-frames 30 --query-frames 10 --force --images").status, 0);
  std::ofstream(path("demo/query/notes.txt")) << "mine";
  const CommandResult kept = run(tool + " --reference-frames 30 --query-frames 10 --force");
  EXPECT_EQ(kept.status, 1);
  EXPECT_NE(kept.err.find("holds 'notes.txt', which make_demo_route did not write"), std::string::npos) << kept.err;
  EXPECT_TRUE(fs::exists(path("demo/query/notes.txt")));
  EXPECT_EQ(count("reference"), 30);
  // An unset shell variable is no folder: the working directory's own folders are not touched.
  const CommandResult empty = run(std::string(MAKE_DEMO_ROUTE_PATH) + " --output '' --force");
  EXPECT_EQ(empty.status, 1);
  EXPECT_NE(empty.err.find("--output was given an empty path"), std::string::npos) << empty.err;
}

TEST_F(BagToolsTest, AStoppedMakeDemoRouteLeavesTheEarlierRouteWhole) {
  const std::string tool = std::string(MAKE_DEMO_ROUTE_PATH) + " --output " + path("stopped_route") + " --images";
  ASSERT_EQ(run(tool + " --reference-frames 30 --query-frames 20").status, 0);
  std::map<std::string, std::string> earlier;
  for (const char* file : {"reference.bag", "query.bag", "ground_truth.csv", "reference/000029.png"}) {
    earlier[file] = fileContents(path("stopped_route/") + file);
  }
  // Stopped while writing the new route's frames, after its bags: everything is written aside first.
  const CommandResult stopped = run(mrs_vpr::testing_support::stoppedOnceExists(
      tool + " --reference-frames 3000 --query-frames 2000 --seed 2 --force", path("stopped_route/reference.part")));
  EXPECT_EQ(stopped.status, 128 + SIGTERM) << stopped.err;
  EXPECT_NE(stopped.err.find("make_demo_route: interrupted by SIGTERM"), std::string::npos) << stopped.err;
  for (const auto& [file, contents] : earlier) {
    EXPECT_EQ(fileContents(path("stopped_route/") + file), contents) << file;
  }
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(path("stopped_route"))) names.push_back(entry.path().filename());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"ground_truth.csv", "query", "query.bag", "reference", "reference.bag"}));
  // A folder of the user's where an interrupted run would have left its own is not removed.
  fs::create_directory(path("stopped_route/query.part"));
  std::ofstream(path("stopped_route/query.part/notes.txt")) << "mine";
  const CommandResult kept = run(tool + " --reference-frames 30 --query-frames 20 --force");
  EXPECT_EQ(kept.status, 1);
  EXPECT_NE(kept.err.find("holds 'notes.txt', which make_demo_route did not write"), std::string::npos) << kept.err;
  EXPECT_TRUE(fs::exists(path("stopped_route/query.part/notes.txt")));
}

TEST_F(BagToolsTest, ImagesToBagLeavesNoPartialBagAndOverwritesOnlyWithForce) {
  const std::string bag = path("route.bag");
  const std::string arguments = " --images " + path("query") + " --bag " + bag + " --topic /t --rate 5";
  ASSERT_EQ(run(std::string(IMAGES_TO_BAG_PATH) + arguments).status, 0);
  const auto size = fs::file_size(bag);
  // An existing bag is kept unless --force says otherwise.
  const CommandResult again = run(std::string(IMAGES_TO_BAG_PATH) + arguments);
  EXPECT_EQ(again.status, 1);
  EXPECT_NE(again.err.find("exists; use --force"), std::string::npos) << again.err;
  EXPECT_EQ(fs::file_size(bag), size);
  EXPECT_EQ(run(std::string(IMAGES_TO_BAG_PATH) + arguments + " --force").status, 0);

  // A truncated image half way: exit 1, and neither a bag nor its temporary file is left.
  fs::create_directories(path("truncated"));
  for (const auto& entry : fs::directory_iterator(path("query"))) {
    fs::copy_file(entry.path(), fs::path(path("truncated")) / entry.path().filename());
  }
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(path("truncated"))) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  fs::resize_file(files[files.size() / 2], 20);
  const std::string broken = path("truncated.bag");
  const CommandResult truncated = run(std::string(IMAGES_TO_BAG_PATH) + " --images " + path("truncated") + " --bag " +
                                      broken + " --topic /t --rate 5");
  EXPECT_EQ(truncated.status, 1) << truncated.err;
  EXPECT_FALSE(fs::exists(broken));
  EXPECT_FALSE(fs::exists(broken + ".part"));
}

TEST_F(BagToolsTest, OutputsThatAreFoldersAreRefusedBeforeAnyWork) {
  // --force onto a folder used to describe every frame, then fail to rename and leave OUT.part.
  fs::create_directories(path("a_folder"));
  const CommandResult map =
      run(buildMap() + " --images " + path("reference") + " --output " + path("a_folder") + " --force");
  EXPECT_EQ(map.status, 1);
  EXPECT_NE(map.err.find("build_map: error: '" + path("a_folder") + "' is a folder; --output names the map file"),
            std::string::npos)
      << map.err;
  EXPECT_EQ(map.err.find("frames"), std::string::npos) << "work was done first: " << map.err;
  EXPECT_FALSE(fs::exists(path("a_folder.part")));
  const CommandResult no_folder =
      run(buildMap() + " --images " + path("reference") + " --output " + path("nowhere/map.db"));
  EXPECT_EQ(no_folder.status, 1);
  EXPECT_NE(no_folder.err.find("there is no folder " + path("nowhere")), std::string::npos) << no_folder.err;
  EXPECT_EQ(no_folder.err.find("frames"), std::string::npos) << no_folder.err;

  const CommandResult bag = run(std::string(IMAGES_TO_BAG_PATH) + " --images " + path("query") + " --bag " +
                                path("a_folder") + " --topic /t --rate 5 --force");
  EXPECT_EQ(bag.status, 1);
  EXPECT_NE(bag.err.find("images_to_bag: error: '" + path("a_folder") + "' is a folder; --bag names the bag file"),
            std::string::npos)
      << bag.err;
  EXPECT_EQ(bag.err.find("images in"), std::string::npos) << "work was done first: " << bag.err;
  EXPECT_FALSE(fs::exists(path("a_folder.part")));
  EXPECT_TRUE(fs::is_empty(path("a_folder")));
}

TEST_F(BagToolsTest, ABagNamedThroughALinkIsWrittenWhereTheLinkPoints) {
  // As build_map writes a map named through a link: ~/bags/latest.bag -> today's bag, say.
  fs::create_directories(path("bags"));
  fs::create_symlink("bags/today.bag", path("latest.bag"));
  const std::string write = std::string(IMAGES_TO_BAG_PATH) + " --images " + path("query") + " --bag " +
                            path("latest.bag") + " --rate 5 --start-time 1";
  const CommandResult created = run(write + " --topic /t");
  ASSERT_EQ(created.status, 0) << created.err;
  EXPECT_TRUE(fs::is_symlink(path("latest.bag")));
  ASSERT_TRUE(fs::is_regular_file(path("bags/today.bag")));
  const std::string first_bytes = fileContents(path("bags/today.bag"));
  // Replaced with --force through the link, the link stays and the file it names is the new bag.
  const CommandResult refused = run(write + " --topic /t");
  EXPECT_EQ(refused.status, 1);
  EXPECT_NE(refused.err.find("exists; use --force to replace it"), std::string::npos) << refused.err;
  const CommandResult replaced = run(write + " --topic /other --force");
  ASSERT_EQ(replaced.status, 0) << replaced.err;
  EXPECT_TRUE(fs::is_symlink(path("latest.bag")));
  EXPECT_NE(fileContents(path("bags/today.bag")), first_bytes);
  EXPECT_EQ(fileContents(path("latest.bag")), fileContents(path("bags/today.bag")));
  // A link to a pipe (or a device, such as /dev/null): the finished bag would replace it.
  ASSERT_EQ(::mkfifo(path("pipe").c_str(), 0600), 0);
  fs::create_symlink(path("pipe"), path("to_pipe.bag"));
  for (const std::string& named : {path("pipe"), path("to_pipe.bag")}) {
    const CommandResult refused_pipe = run(std::string(IMAGES_TO_BAG_PATH) + " --images " + path("query") +
                                           " --bag " + named + " --topic /t --rate 5 --force");
    EXPECT_EQ(refused_pipe.status, 1);
    EXPECT_NE(refused_pipe.err.find("images_to_bag: error: --bag '" + path("pipe") +
                                    "' is no regular file (a device, a pipe or a socket)"),
              std::string::npos)
        << refused_pipe.err;
  }
  EXPECT_TRUE(fs::is_fifo(path("pipe")));
  EXPECT_TRUE(fs::is_symlink(path("to_pipe.bag")));
}

TEST_F(BagToolsTest, ImagesToBagNamesTheFilesOfTheFolderThatAreNoImages) {
  fs::create_directories(path("with_notes"));
  for (const std::string& image : mrs_vpr::listImageFiles(path("query"))) {
    fs::copy_file(image, path("with_notes") + "/" + fs::path(image).filename().string());
    if (fs::path(image).filename() == "00004.png") break;
  }
  std::ofstream(path("with_notes/zz.jfif")) << "an image of another name\n";
  const CommandResult written = run(std::string(IMAGES_TO_BAG_PATH) + " --images " + path("with_notes") + " --bag " +
                                    path("with_notes.bag") + " --topic /t --rate 5");
  ASSERT_EQ(written.status, 0) << written.err;
  EXPECT_NE(written.err.find("images_to_bag: left out 1 file of '" + path("with_notes") +
                             "' not named as an image (zz.jfif)"),
            std::string::npos)
      << written.err;
  EXPECT_NE(written.err.find("wrote 5 images"), std::string::npos) << written.err;
}

TEST_F(BagToolsTest, NoToolWritesOverWhatItReads) {
  const std::string bag = path("own_input.bag");
  ASSERT_EQ(run(std::string(IMAGES_TO_BAG_PATH) + " --images " + path("query") + " --bag " + bag +
                " --topic /t --rate 5").status,
            0);
  const std::string bag_bytes = fileContents(bag);
  const std::string first_image = mrs_vpr::listImageFiles(path("reference")).front();
  const std::string image_bytes = fileContents(first_image);
  const auto refused = [](const CommandResult& result, const std::string& text) {
    EXPECT_EQ(result.status, 1) << result.err;
    EXPECT_NE(result.err.find(text), std::string::npos) << result.err;
  };
  refused(run(buildMap() + " --bag " + bag + " --topic /t --output " + bag + " --force"),
          "build_map: error: --output '" + bag + "' is what --bag reads: write it elsewhere");
  refused(run(buildMap() + " --images " + path("reference") + " --output " + path("reference/map.db")),
          "--output '" + path("reference/map.db") + "' lies inside the folder '" + path("reference") +
              "' that --images reads");
  refused(run(std::string(IMAGES_TO_BAG_PATH) + " --images " + path("reference") + " --bag " + first_image +
              " --topic /t --rate 5 --force"),
          "images_to_bag: error: --bag '" + first_image + "' lies inside the folder");
  refused(run(eval("--reference " + bag + " --query " + path("query") + " --topic /t --protocol per-frame --output " +
                   bag)),
          "mrs_vpr_eval: error: --output '" + bag + "' is what --reference reads");
  refused(run(eval("--reference " + path("reference") + " --query " + path("query") + " --protocol per-frame --plots " +
                   path("query/plots"))),
          "--plots '" + path("query/plots") + "' lies inside the folder '" + path("query") + "' that --query reads");
  refused(run(std::string(MAKE_DRIVE_PATH) + " --images " + path("reference") + " --output " +
              path("reference/drive")),
          "make_drive: error: --output '" + path("reference/drive") + "' lies inside the folder");
  // mrs_vpr_eval writes through a link (into a pipe, say), and into the folder a link names: a link to an
  // input is refused as the input itself.
  fs::create_symlink(bag, path("bag_link.json"));
  refused(run(eval("--reference " + bag + " --query " + path("query") + " --topic /t --protocol per-frame --output " +
                   path("bag_link.json"))),
          "mrs_vpr_eval: error: --output '" + path("bag_link.json") + "' is what --reference reads");
  fs::create_symlink(first_image, path("image_link.json"));
  refused(run(eval("--reference " + path("reference") + " --query " + path("query") + " --protocol per-frame --output " +
                   path("image_link.json"))),
          "--output '" + path("image_link.json") + "' lies inside the folder '" + path("reference") + "'");
  const std::size_t query_images = mrs_vpr::listImageFiles(path("query")).size();
  fs::create_directory_symlink(path("query"), path("query_link"));
  refused(run(eval("--reference " + path("reference") + " --query " + path("query") + " --protocol per-frame --plots " +
                   path("query_link"))),
          "--plots '" + path("query_link") + "' is what --query reads");
  EXPECT_EQ(fileContents(bag), bag_bytes);
  EXPECT_EQ(fileContents(first_image), image_bytes);
  EXPECT_EQ(mrs_vpr::listImageFiles(path("query")).size(), query_images);
  EXPECT_EQ(std::distance(fs::directory_iterator(path("query")), fs::directory_iterator()),
            static_cast<std::ptrdiff_t>(query_images));
  EXPECT_FALSE(fs::exists(path("reference/map.db")));
  EXPECT_FALSE(fs::exists(path("query/plots")));
  EXPECT_FALSE(fs::exists(path("reference/drive")));
}

TEST_F(BagToolsTest, ImagesToBagStampsExactlyAndRefusesWhatNoBagCanHold) {
  // 100 frames at 10 Hz up to 9.9 s before the latest ROS time: through doubles, the stamps there
  // are off by up to half a microsecond.
  const std::string bag = path("late.bag");
  const std::string images = " --images " + path("query") + " --topic /camera/image_raw";
  const CommandResult late =
      run(std::string(IMAGES_TO_BAG_PATH) + images + " --bag " + bag + " --rate 10 --start-time 4294967286");
  ASSERT_EQ(late.status, 0) << late.err;
  const auto written = mrs_vpr::bag::readImages(bag, "/camera/image_raw", 0, 100);
  for (std::uint32_t i = 0; i < 100; ++i) {
    EXPECT_EQ(written[i]->header.stamp, ros::Time(4294967286U + i / 10, (i % 10) * 100000000U)) << i;
  }
  // Stamps beyond 4294967295.999999999 s: refused before anything is written.
  for (const std::string& timing : {std::string(" --rate 1e-300 --start-time 1000"),
                                    std::string(" --rate 10 --start-time 4294967290")}) {
    SCOPED_TRACE(timing);
    const CommandResult result = run(std::string(IMAGES_TO_BAG_PATH) + images + " --bag " + path("never.bag") + timing);
    EXPECT_EQ(result.status, 1);
    EXPECT_NE(result.err.find("images_to_bag: error: the images cannot all be stamped: frame "), std::string::npos)
        << result.err;
    EXPECT_NE(result.err.find("beyond the latest ROS time (4294967295.999999999 s); use a higher --rate or an "
                              "earlier --start-time"),
              std::string::npos)
        << result.err;
    EXPECT_FALSE(fs::exists(path("never.bag")));
  }
  // Before a bag's earliest time, 1 ns: rosbag's own message came from deep inside it; NaN named.
  for (const std::string& start : {"1e-10", "0", "nan"}) {
    const CommandResult early = run(std::string(IMAGES_TO_BAG_PATH) + images + " --bag " + path("never.bag") +
                                    " --rate 10 --start-time " + start);
    EXPECT_EQ(early.status, 1);
    EXPECT_NE(early.err.find("images_to_bag: error: --start-time must be at least 1 ns (a bag cannot hold time 0), "
                             "got "),
              std::string::npos)
        << early.err;
    EXPECT_FALSE(fs::exists(path("never.bag")));
  }
  const CommandResult topic = run(std::string(IMAGES_TO_BAG_PATH) + " --images " + path("query") + " --bag " +
                                  path("never.bag") + " --topic 'bad topic!' --rate 10");
  EXPECT_EQ(topic.status, 1);
  EXPECT_NE(topic.err.find("--topic 'bad topic!' is not a valid ROS topic name: "), std::string::npos) << topic.err;
  EXPECT_FALSE(fs::exists(path("never.bag")));
}

TEST_F(BagToolsTest, BuildMapReadsTheBagItIsGivenWhateverItsNameAndKeepsItsStampsExact) {
  // A frame stamped at the latest ROS time, in a bag whose name does not end in .bag.
  const std::string bag = path("latest.recording");
  {
    rosbag::Bag writer(bag, rosbag::bagmode::Write);
    const cv::Mat image = cv::imread(path("reference/00000.png"));
    for (std::uint32_t i = 0; i < 3; ++i) {
      const ros::Time stamp(4294967295U, 999999997U + i);
      writer.write("/camera/image_raw", stamp, mrs_vpr::bag::toImageMessage(image, "bgr8", stamp, "camera", i));
    }
  }
  const CommandResult built =
      run(buildMap() + " --bag " + bag + " --topic /camera/image_raw --output " + path("latest.db"));
  ASSERT_EQ(built.status, 0) << built.err;
  std::vector<mrs_vpr::Stamp> stamps;
  mrs_vpr::MapDatabase(path("latest.db"), mrs_vpr::MapAccess::kReadOnly)
      .forEachFrame([&](const mrs_vpr::StoredFrame& frame) { stamps.push_back(frame.stamp); });
  ASSERT_EQ(stamps.size(), 3U);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(stamps[i].nanoseconds(), mrs_vpr::Stamp::kMaxNanoseconds - 2 + i);

  // A file that is no bag is named as such, not as a folder.
  std::ofstream(path("garbage.db")) << "garbage";
  const CommandResult garbage = run(buildMap() + " --bag " + path("garbage.db") +
                                    " --topic /camera/image_raw --output " + path("garbage_map.db"));
  EXPECT_EQ(garbage.status, 1);
  EXPECT_NE(garbage.err.find("build_map: error: cannot open bag '" + path("garbage.db") + "'"), std::string::npos)
      << garbage.err;
  EXPECT_EQ(garbage.err.find("is not a folder"), std::string::npos) << garbage.err;
  EXPECT_EQ(garbage.err.find("rosbag reindex"), std::string::npos) << garbage.err;
  // A recording cut short is a bag without its index at the end, which rosbag reindex mends.
  const std::string whole = fileContents(bag);
  std::ofstream(path("cut_short.bag"), std::ios::binary) << whole.substr(0, whole.size() / 2);
  const CommandResult cut_short = run(buildMap() + " --bag " + path("cut_short.bag") +
                                      " --topic /camera/image_raw --output " + path("cut_short.db"));
  EXPECT_EQ(cut_short.status, 1);
  EXPECT_NE(cut_short.err.find("cannot open bag '" + path("cut_short.bag") + "'"), std::string::npos) << cut_short.err;
  EXPECT_NE(cut_short.err.find("can be mended with `rosbag reindex`"), std::string::npos) << cut_short.err;
}

TEST_F(BagToolsTest, AMessageThatCannotBeReadIsNamedByItsIndexTopicAndBag) {
  const cv::Mat image = cv::imread(path("reference/00000.png"));
  const std::string corrupt = path("corrupt.bag");
  {
    rosbag::Bag writer(corrupt, rosbag::bagmode::Write);
    const ros::Time stamp(100, 0);
    writer.write("/camera/image_raw", stamp, mrs_vpr::bag::toImageMessage(image, "bgr8", stamp, "camera", 0));
    writer.write("/camera/image_raw", stamp + ros::Duration(0.1), CorruptImage{{1, 2, 3, 4, 5, 6, 7}});
  }
  const CommandResult cut = run(buildMap() + " --bag " + corrupt + " --topic /camera/image_raw --output " +
                                path("corrupt.db"));
  EXPECT_EQ(cut.status, 1);
  EXPECT_NE(cut.err.find("build_map: error: message 1 of topic '/camera/image_raw' in bag '" + corrupt +
                         "' cannot be read: "),
            std::string::npos)
      << cut.err;
  EXPECT_FALSE(fs::exists(path("corrupt.db")));

  const std::string empty = path("empty_compressed.bag");
  {
    rosbag::Bag writer(empty, rosbag::bagmode::Write);
    sensor_msgs::CompressedImage compressed;
    compressed.header.stamp = ros::Time(100, 0);
    compressed.format = "jpeg";
    writer.write("/camera/image_raw/compressed", compressed.header.stamp, compressed);
  }
  const CommandResult nothing = run(buildMap() + " --bag " + empty + " --topic /camera/image_raw/compressed --output " +
                                    path("empty.db"));
  EXPECT_EQ(nothing.status, 1);
  EXPECT_NE(nothing.err.find("message 0 of topic '/camera/image_raw/compressed' in bag '" + empty +
                             "' cannot be read: the compressed image holds no data (0 bytes)"),
            std::string::npos)
      << nothing.err;
  EXPECT_EQ(nothing.err.find("OpenCV("), std::string::npos) << nothing.err;

  // An encoding no front end reads: query_bag names the message too (no master is needed to find it).
  const std::string depth = path("depth.bag");
  {
    rosbag::Bag writer(depth, rosbag::bagmode::Write);
    sensor_msgs::Image image;
    image.header.stamp = ros::Time(100, 0);
    image.height = 8;
    image.width = 8;
    image.encoding = "32FC1";
    image.step = 8 * sizeof(float);
    image.data.assign(image.step * image.height, 0);
    writer.write("/depth", image.header.stamp, image);
    image.header.stamp = ros::Time(101, 0);
    writer.write("/depth", image.header.stamp, image);
  }
  const CommandResult unread = run(std::string(QUERY_BAG_PATH) + " --bag " + depth + " --topic /depth --count 2");
  EXPECT_EQ(unread.status, 1);
  EXPECT_NE(unread.err.find("query_bag: error: message 0 of topic '/depth' in bag '" + depth + "': "),
            std::string::npos)
      << unread.err;
}

}  // namespace
