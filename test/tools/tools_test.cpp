// Runs the installed command-line tools (mrs_vpr_eval, images_to_bag, ..., and the benchmarks) on
// generated data in a temporary folder: results, JSON fields, and one-line errors with exit code 1 on
// bad input.

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <rosbag/bag.h>

#include "mrs_vpr/acceptance.hpp"
#include "mrs_vpr/node/bag_images.hpp"
#include "mrs_vpr/parameters.hpp"
#include "mrs_vpr/store/map_database.hpp"
#include "mrs_vpr/synthetic_route.hpp"
#include "route_folders.hpp"
#include "support/travel_bag.hpp"

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

struct Result {
  int status = -1;
  std::string out;
  std::string err;
};

std::string readText(const fs::path& path) {
  std::ifstream file(path);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

/// A generated route written as image folders once for all tests of this file.
class ToolsTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    root_ = fs::temp_directory_path() / ("mrs_vpr_tools_test_" + std::to_string(::getpid()));
    fs::remove_all(root_);
    mrs_vpr::testing_support::writeRouteFolders(root_);
  }
  static void TearDownTestSuite() {
    std::error_code ignored;
    fs::remove_all(root_, ignored);
  }

  /// Runs `command` (arguments already quoted) and captures its exit status, stdout and stderr.
  static Result run(const std::string& command) {
    const fs::path out = root_ / "stdout.txt";
    const fs::path err = root_ / "stderr.txt";
    const int raw = std::system((command + " >'" + out.string() + "' 2>'" + err.string() + "'").c_str());
    Result result;
    result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    result.out = readText(out);
    result.err = readText(err);
    return result;
  }

  /// mrs_vpr_eval and build_map as these tests use them on the generated route: every frame a keyframe,
  /// as they count its frames, and the thumbnail front end its textures were made for
  /// (support/route_fixture.hpp). Both defaults have tests of their own.
  static std::string eval(const std::string& arguments) {
    return std::string(MRS_VPR_EVAL_PATH) + " --min-appearance-change 0 --descriptor thumbnail " + arguments;
  }
  static std::string buildMap() {
    return std::string(BUILD_MAP_PATH) + " --min-appearance-change 0 --descriptor thumbnail";
  }
  static std::string path(const std::string& child) { return (root_ / child).string(); }

  /// Expects exit code 1 and exactly one line on stderr that contains `text`.
  static void expectError(const std::string& arguments, const std::string& text) {
    const Result result = run(eval(arguments));
    EXPECT_EQ(result.status, 1) << arguments << "\n" << result.err;
    EXPECT_NE(result.err.find(text), std::string::npos) << result.err;
    const std::string last_line = result.err.substr(result.err.rfind('\n', result.err.size() - 2) + 1);
    EXPECT_EQ(last_line.rfind("mrs_vpr_eval: error: ", 0), 0U) << result.err;
    EXPECT_NE(last_line.find(text), std::string::npos) << result.err;
  }

  static fs::path root_;
};

fs::path ToolsTest::root_;

TEST_F(ToolsTest, PerFrameSeqSlamFindsThePlantedAlignment) {
  const std::string output = path("per_frame.json");
  const Result result =
      run(eval("--reference " + path("reference") + " --query " + path("query") + " --ground-truth " +
               path("truth.csv") + " --method seqslam --protocol per-frame --sequence-length 10 --alignment causal --tolerance 2 --output " +
               output));
  ASSERT_EQ(result.status, 0) << result.err;
  const json document = json::parse(readText(output));
  const json& summary = document.at("summary");
  for (const char* field : {"tolerance", "queries", "top1", "pr_auc", "recall_at_100_precision", "median_abs_error",
                            "largest_wrong_accepted_error", "median_time_ms", "total_time_s"}) {
    EXPECT_TRUE(summary.contains(field)) << field;
  }
  EXPECT_EQ(summary.at("queries").get<int>(), 91);  // Query frames 9..99 have 10 frames behind them.
  EXPECT_EQ(summary.at("tolerance").get<int>(), 2);
  EXPECT_GE(summary.at("top1").get<double>(), 0.9);
  EXPECT_GE(summary.at("pr_auc").get<double>(), 0.9);
  EXPECT_EQ(document.at("parameters").at("sequence").at("sequence_length").get<int>(), 10);
  EXPECT_EQ(document.at("protocol"), "per-frame");
  const json& record = document.at("records").at(0);
  EXPECT_EQ(record.at("query_index").get<int>(), 9);
  for (const char* field : {"query_index", "true_index", "predicted_index", "score", "confidence", "time_ms"}) {
    EXPECT_TRUE(record.contains(field)) << field;
  }
  // The summary also goes to stdout.
  EXPECT_EQ(json::parse(result.out).at("summary").at("queries").get<int>(), 91);
}

TEST_F(ToolsTest, GlobalProtocolIsSeededAndUsesKSequences) {
  const std::string arguments = "--reference " + path("reference") + " --query " + path("query") + " --ground-truth " +
                                path("truth.csv") + " --method seqslam --protocol global --sequence-length 40 --alignment causal " +
                                "--queries 12 --tolerance 5 --seed 3 --output ";
  ASSERT_EQ(run(eval(arguments + path("global_a.json"))).status, 0);
  ASSERT_EQ(run(eval(arguments + path("global_b.json"))).status, 0);
  const json a = json::parse(readText(path("global_a.json")));
  const json b = json::parse(readText(path("global_b.json")));
  ASSERT_EQ(a.at("records").size(), 12U);
  for (std::size_t i = 0; i < 12; ++i) {
    EXPECT_EQ(a["records"][i]["query_index"], b["records"][i]["query_index"]);
    EXPECT_GE(a["records"][i]["query_index"].get<int>(), 39);
  }
  EXPECT_GE(a.at("summary").at("top1").get<double>(), 0.9);
}

TEST_F(ToolsTest, BadInputGivesOneLineAndExitCodeOne) {
  const std::string folders = "--reference " + path("reference") + " --query " + path("query");
  expectError("--reference " + path("nowhere") + " --query " + path("query") +
                  " --method seqslam --protocol per-frame --sequence-length 10",
              "image folder '" + path("nowhere") + "' does not exist");
  expectError(folders + " --method fastest --protocol per-frame --sequence-length 10", "unknown method 'fastest'");
  expectError(folders + " --method mrs --protocol sideways --sequence-length 10", "unknown protocol 'sideways'");
  expectError(folders + " --method seqslam --protocol global --sequence-length 151",
              "sequence length 151 is larger than the reference of 150 keyframes");
  expectError(folders + " --method seqslam --sequence-length 10", "protocol");  // Missing flag.
  // A word of no option (e.g. a second value) is refused, not silently dropped.
  expectError(folders + " --method seqslam --protocol per-frame --sequence-length 10 20", "unexpected argument '20'");

  // An unreadable image, named.
  fs::create_directories(path("broken"));
  fs::copy_file(path("reference/00000.png"), path("broken/00000.png"), fs::copy_options::overwrite_existing);
  std::ofstream(path("broken/00001.png")) << "not a png";
  expectError("--reference " + path("broken") + " --query " + path("query") +
                  " --method seqslam --protocol per-frame --sequence-length 2",
              "cannot read image '" + path("broken/00001.png") + "'");

  // Different sizes within a folder and between folders.
  fs::create_directories(path("mixed"));
  fs::copy_file(path("reference/00000.png"), path("mixed/00000.png"), fs::copy_options::overwrite_existing);
  cv::imwrite(path("mixed/00001.png"), cv::Mat(10, 10, CV_8UC3, cv::Scalar::all(9)));
  expectError("--reference " + path("mixed") + " --query " + path("query") +
                  " --method seqslam --protocol per-frame --sequence-length 2",
              "00001.png' is 10x10 but");
  fs::create_directories(path("small"));
  for (int i = 0; i < 3; ++i) {
    cv::imwrite(path("small/" + std::to_string(i) + ".png"), cv::Mat(10, 10, CV_8UC3, cv::Scalar::all(i)));
  }
  expectError(folders.substr(0, folders.find(" --query")) + " --query " + path("small") +
                  " --method seqslam --protocol per-frame --sequence-length 2",
              "query images are 10x10 but reference images are 128x64");
}

/// Records of `records` whose boolean `field` is true.
int countTrue(const json& records, const char* field) {
  int count = 0;
  for (const json& record : records) count += record.at(field).get<bool>() ? 1 : 0;
  return count;
}

TEST_F(ToolsTest, RecordsCarryTheAcceptanceRuleAndTheSummaryCountsIt) {
  const std::string arguments = "--reference " + path("reference") + " --query " + path("query") + " --ground-truth " +
                                path("truth.csv") + " --method seqslam --protocol per-frame --sequence-length 20 " +
                                "--tolerance 2 --accept-threshold 2.5 --output ";
  ASSERT_EQ(run(eval(arguments + path("accept_rule.json"))).status, 0);
  const json document = json::parse(readText(path("accept_rule.json")));
  // The fixture's map holds a few dozen places, where 3 would become 3.4: a lower threshold lets
  // some answers through, so that the rule is seen at work.
  EXPECT_DOUBLE_EQ(document.at("parameters").at("sequence").at("accept_threshold").get<double>(), 2.5);
  mrs_vpr::SequenceParams rule;
  rule.accept_threshold = 2.5;
  const json& records = document.at("records");
  const json& summary = document.at("summary");
  for (const char* field : {"accepted", "accepted_rate", "accepted_precision", "accepted_recall"}) {
    EXPECT_TRUE(summary.contains(field)) << field;
  }
  int accepted = 0;
  int accepted_correct = 0;
  for (const json& record : records) {
    ASSERT_TRUE(record.at("accepted").is_boolean()) << record;
    // The core's rule, the same for every method: found, confidence >= the threshold (raised among
    // fewer than 100 places), a trajectory inside the velocity bounds and a test sequence of distinct views.
    const double required = mrs_vpr::requiredConfidence(record.at("rival_places").get<int>(), rule);
    EXPECT_GE(required, 2.5);
    const bool expected = record.at("predicted_index").get<int>() >= 0 &&
                          record.at("confidence").get<double>() >= required &&
                          !record.at("at_velocity_bound").get<bool>() && !record.at("repeated_view").get<bool>();
    EXPECT_EQ(record.at("accepted").get<bool>(), expected) << record;
    accepted += expected ? 1 : 0;
    accepted_correct += expected && record.at("correct").get<bool>() ? 1 : 0;
  }
  const int queries = summary.at("queries").get<int>();
  ASSERT_EQ(queries, static_cast<int>(records.size()));
  EXPECT_EQ(summary.at("accepted").get<int>(), accepted);
  EXPECT_GT(accepted, 0);  // 20 frames of the route stand out of the noise often enough.
  EXPECT_LT(accepted, queries);
  EXPECT_DOUBLE_EQ(summary.at("accepted_rate").get<double>(), static_cast<double>(accepted) / queries);
  EXPECT_DOUBLE_EQ(summary.at("accepted_precision").get<double>(), static_cast<double>(accepted_correct) / accepted);
  EXPECT_DOUBLE_EQ(summary.at("accepted_recall").get<double>(), static_cast<double>(accepted_correct) / queries);
}

TEST_F(ToolsTest, AcceptThresholdZeroAcceptsEveryAnswerAndAThousandNone) {
  const std::string arguments = "--reference " + path("reference") + " --query " + path("query") + " --ground-truth " +
                                path("truth.csv") + " --method seqslam --protocol per-frame --sequence-length 10 " +
                                "--tolerance 2 --output ";
  ASSERT_EQ(run(eval(arguments + path("accept_all.json") + " --accept-threshold 0")).status, 0);
  ASSERT_EQ(run(eval(arguments + path("accept_none.json") + " --accept-threshold 1000")).status, 0);
  const json all = json::parse(readText(path("accept_all.json")));
  const json none = json::parse(readText(path("accept_none.json")));
  EXPECT_DOUBLE_EQ(all.at("parameters").at("sequence").at("accept_threshold").get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(none.at("parameters").at("sequence").at("accept_threshold").get<double>(), 1000.0);

  // Threshold 0: every found answer is accepted (every complete sequence has one here).
  const json& every = all.at("records");
  ASSERT_EQ(every.size(), 91U);
  for (const json& record : every) {
    ASSERT_GE(record.at("predicted_index").get<int>(), 0) << record;
    EXPECT_TRUE(record.at("accepted").get<bool>()) << record;
  }
  const json& summary_all = all.at("summary");
  EXPECT_EQ(summary_all.at("accepted").get<int>(), 91);
  EXPECT_DOUBLE_EQ(summary_all.at("accepted_rate").get<double>(), 1.0);
  // Accepting everything, precision and recall are the top-1 rate.
  EXPECT_DOUBLE_EQ(summary_all.at("accepted_precision").get<double>(), summary_all.at("top1").get<double>());
  EXPECT_DOUBLE_EQ(summary_all.at("accepted_recall").get<double>(), summary_all.at("top1").get<double>());

  // Threshold 1000: nothing is accepted; precision is undefined (null), not 0 or 1.
  EXPECT_EQ(countTrue(none.at("records"), "accepted"), 0);
  const json& summary_none = none.at("summary");
  EXPECT_EQ(summary_none.at("accepted").get<int>(), 0);
  EXPECT_DOUBLE_EQ(summary_none.at("accepted_rate").get<double>(), 0.0);
  EXPECT_TRUE(summary_none.at("accepted_precision").is_null()) << summary_none;
  EXPECT_DOUBLE_EQ(summary_none.at("accepted_recall").get<double>(), 0.0);
  // The threshold decides acceptance only: the answers themselves are the same.
  ASSERT_EQ(none.at("records").size(), every.size());
  for (std::size_t i = 0; i < every.size(); ++i) {
    EXPECT_EQ(none["records"][i]["predicted_index"], every[i]["predicted_index"]) << i;
    EXPECT_EQ(none["records"][i]["confidence"], every[i]["confidence"]) << i;
  }
}

TEST_F(ToolsTest, OutOfMapQueriesHaveNoTrueIndexAndEveryAcceptedAnswerIsFalse) {
  const std::string arguments = "--reference " + path("reference") + " --query " + path("query") +
                                " --out-of-map --method seqslam --protocol per-frame --sequence-length 20 --output ";
  // At the default threshold, and at 0 where every answer is accepted (the route's query is in fact
  // in the map, so only --out-of-map makes them false).
  for (const std::string threshold : {"3", "0"}) {
    const std::string output = path("out_of_map_" + threshold + ".json");
    const Result result = run(eval(arguments + output + " --accept-threshold " + threshold));
    ASSERT_EQ(result.status, 0) << result.err;
    const json document = json::parse(readText(output));
    EXPECT_TRUE(document.at("parameters").at("out_of_map").get<bool>());
    const json& records = document.at("records");
    const json& summary = document.at("summary");
    EXPECT_EQ(summary.at("queries").get<int>(), 81) << threshold;  // Every frame 19..99 is a query.
    ASSERT_EQ(records.size(), 81U);
    for (const json& record : records) {
      EXPECT_TRUE(record.at("true_index").is_null()) << record;
      EXPECT_TRUE(record.at("true_indices").empty()) << record;
      EXPECT_FALSE(record.at("correct").get<bool>()) << record;
      EXPECT_TRUE(record.at("accepted").is_boolean()) << record;
    }
    const int accepted = countTrue(records, "accepted");
    EXPECT_EQ(summary.at("accepted").get<int>(), accepted) << threshold;
    // The false loop-closure rate.
    EXPECT_DOUBLE_EQ(summary.at("accepted_rate").get<double>(), static_cast<double>(accepted) / 81) << threshold;
    EXPECT_DOUBLE_EQ(summary.at("accepted_recall").get<double>(), 0.0) << threshold;
    EXPECT_DOUBLE_EQ(summary.at("top1").get<double>(), 0.0) << threshold;
    if (accepted == 0) {
      EXPECT_TRUE(summary.at("accepted_precision").is_null()) << summary;
    } else {
      EXPECT_DOUBLE_EQ(summary.at("accepted_precision").get<double>(), 0.0) << summary;
    }
    if (threshold == "0") EXPECT_EQ(accepted, 81);
  }
}

TEST_F(ToolsTest, AcceptanceOptionsAreChecked) {
  const std::string folders = "--reference " + path("reference") + " --query " + path("query") +
                              " --method seqslam --protocol per-frame --sequence-length 10";
  // A query cannot be both outside the map and have a true place in it.
  expectError(folders + " --out-of-map --ground-truth " + path("truth.csv"),
              "--out-of-map and --ground-truth exclude each other");
  expectError(folders + " --threads -1", "--threads must be >= 0");
  expectError(folders + " --queries 1000000", "--queries must be in 1..100000");
  expectError(folders + " --accept-threshold -1", "sequence/accept_threshold");
  expectError(folders + " --accept-threshold 1001", "sequence/accept_threshold");
  // Nothing is written for rejected options.
  EXPECT_FALSE(fs::exists(path("rejected.json")));
  expectError(folders + " --threads -1 --output " + path("rejected.json"), "--threads must be >= 0");
  EXPECT_FALSE(fs::exists(path("rejected.json")));
}

TEST_F(ToolsTest, BadSeedAndGroundTruthOfOtherTraversalsAreRefused) {
  const std::string folders = "--reference " + path("reference") + " --query " + path("query") +
                              " --method seqslam --protocol global --sequence-length 10";
  // A negative seed used to wrap silently to 2^64 - 1.
  expectError(folders + " --seed -1", "--seed must be >= 0");
  // Reference frames beyond the reference (a file for other traversals) used to give a summary.
  {
    std::ofstream beyond(path("beyond.csv"));
    beyond << "query_index,matching_ref_indices\n0,0\n1,1000 1001\n";
  }
  expectError(folders + " --ground-truth " + path("beyond.csv"), "query frame 1 lists reference frame 1000");
  {
    std::ofstream huge(path("huge.csv"));
    huge << "query_index,matching_ref_indices\n0,999999999\n";
  }
  expectError(folders + " --ground-truth " + path("huge.csv"), "reference frame 999999999");
}

TEST_F(ToolsTest, ThreadCountDoesNotChangeTheAnswers) {
  const std::string arguments = "--reference " + path("reference") + " --query " + path("query") + " --ground-truth " +
                                path("truth.csv") + " --method mrs --protocol global --sequence-length 64 " +
                                "--queries 6 --seed 5 --output ";
  ASSERT_EQ(run(eval(arguments + path("threads_1.json") + " --threads 1")).status, 0);
  ASSERT_EQ(run(eval(arguments + path("threads_2.json") + " --threads 2")).status, 0);
  const json one = json::parse(readText(path("threads_1.json")));
  const json two = json::parse(readText(path("threads_2.json")));
  EXPECT_EQ(one.at("parameters").at("threads").get<int>(), 1);
  EXPECT_EQ(two.at("parameters").at("threads").get<int>(), 2);
  ASSERT_EQ(one.at("records").size(), 6U);
  ASSERT_EQ(two.at("records").size(), 6U);
  for (std::size_t i = 0; i < 6; ++i) {
    for (const char* field : {"query_index", "predicted_index", "confidence", "accepted"}) {
      EXPECT_EQ(one["records"][i][field], two["records"][i][field]) << i << " " << field;
    }
  }
}

TEST_F(ToolsTest, ImagesToBagWritesIncreasingStampsAndTheEvaluatorReadsBags) {
  for (const char* traversal : {"reference", "query"}) {
    const Result result = run(std::string(IMAGES_TO_BAG_PATH) + " --images " + path(traversal) + " --bag " +
                              path(std::string(traversal) + ".bag") +
                              " --topic /camera/image_raw --rate 10 --start-time 1000");
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

  // Same frames from bags as from folders: the same answers.
  const std::string common = " --ground-truth " + path("truth.csv") +
                             " --method seqslam --protocol per-frame --sequence-length 10 --output ";
  ASSERT_EQ(run(eval("--reference " + path("reference") + " --query " + path("query") + common +
                     path("folders.json")))
                .status,
            0);
  const Result from_bags = run(eval("--reference " + path("reference.bag") + " --query " + path("query.bag") +
                                    " --topic /camera/image_raw" + common + path("bags.json")));
  ASSERT_EQ(from_bags.status, 0) << from_bags.err;
  const json folders = json::parse(readText(path("folders.json")));
  const json bags = json::parse(readText(path("bags.json")));
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
TEST_F(ToolsTest, TheEvaluatorLoadsTheBagReaderOnlyWhenItReadsABag) {
  const Result help = run("LD_DEBUG=files " + eval("--help"));
  ASSERT_EQ(help.status, 0) << help.err;
  ASSERT_NE(help.err.find("libmrs_vpr_core.so"), std::string::npos) << "LD_DEBUG gave no listing";
  EXPECT_EQ(help.err.find("librosbag_storage"), std::string::npos);
  EXPECT_EQ(help.err.find("libmrs_vpr_rosbag_reader"), std::string::npos);

  const Result written = run(std::string(IMAGES_TO_BAG_PATH) + " --images " + path("reference") + " --bag " +
                             path("lazy.bag") + " --topic /camera/image_raw --rate 10");
  ASSERT_EQ(written.status, 0) << written.err;
  const std::string arguments = "--reference " + path("lazy.bag") + " --query " + path("query") +
                                " --topic /camera/image_raw --ground-truth " + path("truth.csv") +
                                " --method seqslam --protocol per-frame --sequence-length 10";
  const Result from_bag = run("LD_DEBUG=files " + eval(arguments));
  ASSERT_EQ(from_bag.status, 0) << from_bag.err;
  EXPECT_NE(from_bag.err.find("libmrs_vpr_rosbag_reader.so"), std::string::npos);
  EXPECT_NE(from_bag.err.find("librosbag_storage"), std::string::npos);
}

TEST_F(ToolsTest, ImagesToBagRejectsBadArguments) {
  const Result no_rate = run(std::string(IMAGES_TO_BAG_PATH) + " --images " + path("query") + " --bag " +
                             path("x.bag") + " --topic /t --rate 0");
  EXPECT_EQ(no_rate.status, 1);
  EXPECT_NE(no_rate.err.find("--rate must be > 0"), std::string::npos) << no_rate.err;
  const Result no_folder = run(std::string(IMAGES_TO_BAG_PATH) + " --images " + path("nowhere") + " --bag " +
                               path("x.bag") + " --topic /t --rate 5");
  EXPECT_EQ(no_folder.status, 1);
  EXPECT_NE(no_folder.err.find("does not exist"), std::string::npos) << no_folder.err;
  EXPECT_FALSE(fs::exists(path("x.bag")));  // Nothing written for a bad folder.
  const Result no_topic = run(std::string(IMAGES_TO_BAG_PATH) + " --images " + path("query") + " --bag " +
                              path("x.bag") + " --topic '' --rate 5");
  EXPECT_EQ(no_topic.status, 1);
  EXPECT_NE(no_topic.err.find("--topic must not be empty"), std::string::npos) << no_topic.err;
}

TEST_F(ToolsTest, ByDefaultBuildMapAndTheEvaluatorKeepOnlyFramesWhoseViewChanged) {
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
  const Result built = run(std::string(BUILD_MAP_PATH) + " --images " + path("stopped") + " --output " + path("stopped.db"));
  ASSERT_EQ(built.status, 0) << built.err;
  // Every stopped frame is too similar to the frame the robot stopped at; of the moving ones, a few.
  const std::size_t too_similar = built.err.find(" frames too similar");
  ASSERT_NE(too_similar, std::string::npos) << built.err;
  const int skipped = std::stoi(built.err.substr(built.err.rfind(' ', too_similar - 1) + 1));
  EXPECT_GE(skipped, 40) << built.err;
  EXPECT_LT(skipped, 40 + 20) << built.err;

  // The evaluator keeps the same keyframes of the reference, and names frames in its records.
  const std::string output = path("stopped.json");
  const Result evaluated = run(std::string(MRS_VPR_EVAL_PATH) + " --reference " + path("stopped") + " --query " +
                               path("query") + " --protocol per-frame --sequence-length 10 --output " + output);
  ASSERT_EQ(evaluated.status, 0) << evaluated.err;
  const json document = json::parse(readText(output));
  EXPECT_EQ(document.at("reference_frames"), 190);
  EXPECT_EQ(document.at("reference_keyframes"), 190 - skipped);
  EXPECT_EQ(document.at("parameters").at("min_appearance_change"), mrs_vpr::RecognizerParams{}.min_appearance_change);
  EXPECT_EQ(document.at("parameters").at("method"), mrs_vpr::RecognizerParams{}.default_method);
  for (const json& record : document.at("records")) {
    // The keyframe of the stop stands for all 41 frames of it.
    if (record.at("predicted_index") == 60) EXPECT_EQ(record.at("predicted_last"), 100);
    EXPECT_GE(record.at("predicted_last").get<int>(), record.at("predicted_index").get<int>());
  }
}

TEST_F(ToolsTest, AMapBuiltOfAFolderAnswersAsTheFolderDoes) {
  const std::string map = path("reference.db");
  const std::string build = buildMap() + " --images " + path("reference") + " --output " + map;
  const Result built = run(build);
  ASSERT_EQ(built.status, 0) << built.err;
  EXPECT_NE(built.err.find("150 frames added to 0"), std::string::npos) << built.err;
  EXPECT_FALSE(fs::exists(map + ".part"));

  const std::string rest = " --query " + path("query") + " --ground-truth " + path("truth.csv") +
                           " --method seqslam --protocol per-frame --sequence-length 10 --tolerance 2";
  const Result from_folder = run(eval("--reference " + path("reference") + rest));
  const Result from_map = run(eval("--reference " + map + rest));
  ASSERT_EQ(from_folder.status, 0) << from_folder.err;
  ASSERT_EQ(from_map.status, 0) << from_map.err;
  const auto summary = [](const Result& result) {
    nlohmann::json document = nlohmann::json::parse(result.out).at("summary");
    document.erase("median_time_ms");
    document.erase("total_time_s");
    return document;
  };
  EXPECT_EQ(summary(from_map), summary(from_folder));

  // An existing map is neither replaced nor extended unless asked.
  const Result again = run(build);
  EXPECT_EQ(again.status, 1);
  EXPECT_NE(again.err.find("exists; use --append to extend it or --force to replace it"), std::string::npos);
  const Result appended = run(build + " --append");
  EXPECT_EQ(appended.status, 0) << appended.err;
  EXPECT_NE(appended.err.find("150 frames added to 150"), std::string::npos) << appended.err;

}

TEST_F(ToolsTest, AMapIsReadAndExtendedWithTheFrontEndItRecords) {
  // Without a front-end option the evaluator and build_map --append take the map's own front end;
  // another one named is refused, naming the file and both front ends.
  const std::string build_map = std::string(BUILD_MAP_PATH) + " --images " + path("reference") + " --output " +
                                path("small.db");
  const Result other = run(build_map + " --descriptor thumbnail --image-width 32 --image-height 16");
  ASSERT_EQ(other.status, 0) << other.err;
  const std::string evaluate = std::string(MRS_VPR_EVAL_PATH) + " --reference " + path("small.db") + " --query " +
                               path("query") + " --ground-truth " + path("truth.csv") +
                               " --protocol per-frame --sequence-length 10";
  const Result adopted = run(evaluate + " --output " + path("small.json"));
  ASSERT_EQ(adopted.status, 0) << adopted.err;
  EXPECT_NE(adopted.err.find("thumbnail (32 x 16, patches of 8 px)"), std::string::npos) << adopted.err;
  const json parameters = json::parse(readText(path("small.json"))).at("parameters").at("descriptor");
  EXPECT_EQ(parameters.at("type"), "thumbnail");
  EXPECT_EQ(parameters.at("image_width"), 32);
  const Result refused = run(evaluate + " --descriptor hog");
  EXPECT_EQ(refused.status, 1);
  EXPECT_NE(refused.err.find(path("small.db")), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("holds descriptors of the thumbnail (32 x 16, patches of 8 px) front end, not of the "
                             "hog (128 x 64 window"),
            std::string::npos)
      << refused.err;
  const Result appended = run(build_map + " --append");
  EXPECT_EQ(appended.status, 0) << appended.err;
  const Result mixed = run(build_map + " --append --descriptor hog");
  EXPECT_EQ(mixed.status, 1);
  EXPECT_NE(mixed.err.find("not of the hog"), std::string::npos) << mixed.err;
}

TEST_F(ToolsTest, AMapBuiltOfABagWithMinTravelHasAFrameEachMetre) {
  // The robot drives 4 m, stands still for 30 frames and drives 2 m on (support/travel_bag.hpp).
  const std::string bag = path("drive.bag");
  mrs_vpr::testing_support::writeTravelBag(bag, "/camera/image_raw", mrs_vpr::testing_support::driveStopDrive());
  const std::string build = buildMap() + " --bag " + bag + " --topic /camera/image_raw --output ";
  const Result every_frame = run(build + path("every_frame.db"));
  ASSERT_EQ(every_frame.status, 0) << every_frame.err;
  EXPECT_NE(every_frame.err.find("51 frames added to 0"), std::string::npos) << every_frame.err;

  const Result by_travel = run(build + path("by_travel.db") + " --min-travel 1");
  ASSERT_EQ(by_travel.status, 0) << by_travel.err;
  EXPECT_NE(by_travel.err.find("7 frames added to 0"), std::string::npos) << by_travel.err;
  EXPECT_NE(by_travel.err.find("7 keyframes of 51 frames at min_travel 1 m (44 too near, 0 without a pose"),
            std::string::npos)
      << by_travel.err;

  // Frames tf has no pose for are skipped, and the user is told why.
  const Result unknown_frame = run(build + path("gripper.db") + " --min-travel 1 --base-frame gripper");
  ASSERT_EQ(unknown_frame.status, 0) << unknown_frame.err;
  EXPECT_NE(unknown_frame.err.find("0 frames added to 0"), std::string::npos) << unknown_frame.err;
  EXPECT_NE(unknown_frame.err.find("warning: the first frame without a pose"), std::string::npos)
      << unknown_frame.err;
}

TEST_F(ToolsTest, MinTravelWithoutPosesIsRefusedAndWritesNothing) {
  const std::string no_poses = path("no_poses.bag");
  mrs_vpr::testing_support::writeTravelBag(no_poses, "/camera/image_raw", mrs_vpr::testing_support::driveStopDrive(),
                                           false);
  const Result without_tf = run(buildMap() + " --bag " + no_poses +
                                " --topic /camera/image_raw --min-travel 1 --output " + path("no_poses.db"));
  EXPECT_EQ(without_tf.status, 1);
  EXPECT_NE(without_tf.err.find("has no /tf or /tf_static messages"), std::string::npos) << without_tf.err;
  EXPECT_FALSE(fs::exists(path("no_poses.db")));
  EXPECT_FALSE(fs::exists(path("no_poses.db.part")));

  const Result folder = run(buildMap() + " --images " + path("reference") + " --min-travel 1" +
                            " --output " + path("folder.db"));
  EXPECT_EQ(folder.status, 1);
  EXPECT_NE(folder.err.find("--min-travel needs --bag"), std::string::npos) << folder.err;
  const Result negative = run(buildMap() + " --bag " + no_poses +
                              " --topic /camera/image_raw --min-travel=-1 --output " + path("negative.db"));
  EXPECT_EQ(negative.status, 1);
  EXPECT_NE(negative.err.find("min_travel must be a finite number of metres >= 0"), std::string::npos)
      << negative.err;
  const Result recent = run(std::string(QUERY_BAG_PATH) + " --recent-frames 10 --min-travel 1");
  EXPECT_EQ(recent.status, 1);
  EXPECT_NE(recent.err.find("--min-travel needs --bag, not --recent-frames"), std::string::npos) << recent.err;
}

TEST_F(ToolsTest, QueryBagRefusesATimeoutThatWouldWaitForEver) {
  // No master is needed: the options are checked first. -1 used to wait for the service for ever.
  for (const char* timeout : {"-1", "0", "1e9"}) {
    const Result result = run(std::string(QUERY_BAG_PATH) + " --recent-frames 10 --service /nope/query --timeout " +
                              timeout);
    EXPECT_EQ(result.status, 1) << timeout;
    EXPECT_NE(result.err.find("--timeout must be in (0, 3600] s"), std::string::npos) << result.err;
    EXPECT_TRUE(result.out.empty()) << "stdout holds only the JSON answer: " << result.out;
  }
}

TEST_F(ToolsTest, ImagesToBagLeavesNoPartialBagAndOverwritesOnlyWithForce) {
  const std::string bag = path("route.bag");
  const std::string arguments = " --images " + path("query") + " --bag " + bag + " --topic /t --rate 5";
  ASSERT_EQ(run(std::string(IMAGES_TO_BAG_PATH) + arguments).status, 0);
  const auto size = fs::file_size(bag);
  // An existing bag is kept unless --force says otherwise.
  const Result again = run(std::string(IMAGES_TO_BAG_PATH) + arguments);
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
  const Result truncated = run(std::string(IMAGES_TO_BAG_PATH) + " --images " + path("truncated") + " --bag " + broken +
                               " --topic /t --rate 5");
  EXPECT_EQ(truncated.status, 1) << truncated.err;
  EXPECT_FALSE(fs::exists(broken));
  EXPECT_FALSE(fs::exists(broken + ".part"));
}

TEST_F(ToolsTest, OutputsThatAreFoldersAreRefusedBeforeAnyWork) {
  // --force onto a folder used to describe every frame, then fail to rename and leave OUT.part.
  fs::create_directories(path("a_folder"));
  const Result map = run(buildMap() + " --images " + path("reference") + " --output " +
                         path("a_folder") + " --force");
  EXPECT_EQ(map.status, 1);
  EXPECT_NE(map.err.find("build_map: error: '" + path("a_folder") + "' is a folder; --output names the map file"),
            std::string::npos)
      << map.err;
  EXPECT_EQ(map.err.find("frames"), std::string::npos) << "work was done first: " << map.err;
  EXPECT_FALSE(fs::exists(path("a_folder.part")));
  const Result no_folder = run(buildMap() + " --images " + path("reference") + " --output " +
                               path("nowhere/map.db"));
  EXPECT_EQ(no_folder.status, 1);
  EXPECT_NE(no_folder.err.find("there is no folder " + path("nowhere")), std::string::npos) << no_folder.err;
  EXPECT_EQ(no_folder.err.find("frames"), std::string::npos) << no_folder.err;

  const Result bag = run(std::string(IMAGES_TO_BAG_PATH) + " --images " + path("query") + " --bag " +
                         path("a_folder") + " --topic /t --rate 5 --force");
  EXPECT_EQ(bag.status, 1);
  EXPECT_NE(bag.err.find("images_to_bag: error: '" + path("a_folder") + "' is a folder; --bag names the bag file"),
            std::string::npos)
      << bag.err;
  EXPECT_EQ(bag.err.find("images in"), std::string::npos) << "work was done first: " << bag.err;
  EXPECT_FALSE(fs::exists(path("a_folder.part")));
  EXPECT_TRUE(fs::is_empty(path("a_folder")));
}

TEST_F(ToolsTest, ImagesToBagStampsExactlyAndRefusesWhatNoBagCanHold) {
  // 100 frames at 10 Hz up to 9.9 s before the latest ROS time: through doubles, the stamps there
  // are off by up to half a microsecond.
  const std::string bag = path("late.bag");
  const std::string images = " --images " + path("query") + " --topic /camera/image_raw";
  const Result late = run(std::string(IMAGES_TO_BAG_PATH) + images + " --bag " + bag +
                          " --rate 10 --start-time 4294967286");
  ASSERT_EQ(late.status, 0) << late.err;
  const auto written = mrs_vpr::bag::readImages(bag, "/camera/image_raw", 0, 100);
  for (std::uint32_t i = 0; i < 100; ++i) {
    EXPECT_EQ(written[i]->header.stamp, ros::Time(4294967286U + i / 10, (i % 10) * 100000000U)) << i;
  }
  // Stamps beyond 4294967295.999999999 s: refused before anything is written.
  for (const std::string& timing : {std::string(" --rate 1e-300 --start-time 1000"),
                                    std::string(" --rate 10 --start-time 4294967290")}) {
    SCOPED_TRACE(timing);
    const Result result = run(std::string(IMAGES_TO_BAG_PATH) + images + " --bag " + path("never.bag") + timing);
    EXPECT_EQ(result.status, 1);
    EXPECT_NE(result.err.find("images_to_bag: error: the images cannot all be stamped: frame "), std::string::npos)
        << result.err;
    EXPECT_NE(result.err.find("beyond the latest ROS time (4294967295.999999999 s); use a higher --rate or an "
                              "earlier --start-time"),
              std::string::npos)
        << result.err;
    EXPECT_FALSE(fs::exists(path("never.bag")));
  }
  const Result topic = run(std::string(IMAGES_TO_BAG_PATH) + " --images " + path("query") + " --bag " +
                           path("never.bag") + " --topic 'bad topic!' --rate 10");
  EXPECT_EQ(topic.status, 1);
  EXPECT_NE(topic.err.find("--topic 'bad topic!' is not a valid ROS topic name: "), std::string::npos) << topic.err;
  EXPECT_FALSE(fs::exists(path("never.bag")));
}

TEST_F(ToolsTest, BuildMapReadsTheBagItIsGivenWhateverItsNameAndKeepsItsStampsExact) {
  // A frame stamped at the latest ROS time, in a bag whose name does not end in .bag.
  const std::string bag = path("latest.recording");
  {
    rosbag::Bag writer(bag, rosbag::bagmode::Write);
    const cv::Mat image = cv::imread(path("reference/00000.png"));
    for (std::uint32_t i = 0; i < 3; ++i) {
      const ros::Time stamp(4294967295U, 999999997U + i);
      writer.write("/camera/image_raw", stamp, mrs_vpr::bag::toImageMessage(image, "bgr8", stamp, "camera"));
    }
  }
  const Result built = run(buildMap() + " --bag " + bag + " --topic /camera/image_raw --output " +
                           path("latest.db"));
  ASSERT_EQ(built.status, 0) << built.err;
  std::vector<mrs_vpr::Stamp> stamps;
  mrs_vpr::MapDatabase(path("latest.db"), mrs_vpr::MapAccess::kReadOnly)
      .forEachFrame([&](const mrs_vpr::StoredFrame& frame) { stamps.push_back(frame.stamp); });
  ASSERT_EQ(stamps.size(), 3U);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(stamps[i].nanoseconds(), mrs_vpr::Stamp::kMaxNanoseconds - 2 + i);

  // A file that is no bag is named as such, not as a folder.
  std::ofstream(path("garbage.db")) << "garbage";
  const Result garbage = run(buildMap() + " --bag " + path("garbage.db") +
                             " --topic /camera/image_raw --output " + path("garbage_map.db"));
  EXPECT_EQ(garbage.status, 1);
  EXPECT_NE(garbage.err.find("build_map: error: cannot open bag '" + path("garbage.db") + "'"), std::string::npos)
      << garbage.err;
  EXPECT_EQ(garbage.err.find("is not a folder"), std::string::npos) << garbage.err;
}

TEST_F(ToolsTest, TheEvaluatorChecksWhereItWritesBeforeEvaluating) {
  std::ofstream(path("plain_file")) << "x";
  const std::string evaluation = "--reference " + path("reference") + " --query " + path("query") +
                                 " --method seqslam --protocol per-frame --sequence-length 10";
  const Result plots = run(eval(evaluation + " --plots " + path("plain_file/plots")));
  EXPECT_EQ(plots.status, 1);
  EXPECT_NE(plots.err.find("mrs_vpr_eval: error: --plots '" + path("plain_file/plots") + "': cannot create the folder"),
            std::string::npos)
      << plots.err;
  EXPECT_EQ(plots.err.find("matching"), std::string::npos) << "the evaluation ran first: " << plots.err;
  const Result output = run(eval(evaluation + " --output " + path("nowhere/evaluation.json")));
  EXPECT_EQ(output.status, 1);
  EXPECT_NE(output.err.find("--output '" + path("nowhere/evaluation.json") + "': there is no folder " +
                            path("nowhere")),
            std::string::npos)
      << output.err;
  EXPECT_EQ(output.err.find("matching"), std::string::npos) << output.err;
}

/// A benchmark binary, and one of its comma-separated list options.
struct Benchmark {
  std::string name;
  std::string path;
  std::string required;  ///< The options it cannot run without (values never read by the tests below).
  std::string list_option;
};

std::vector<Benchmark> benchmarks() {
  return {{"mrs_vpr_benchmark", MRS_VPR_BENCHMARK_PATH, "", "--threads"},
          {"mrs_vpr_real_benchmark", MRS_VPR_REAL_BENCHMARK_PATH, "--data nowhere", "--lengths"},
          {"mrs_vpr_map_scale_benchmark", MRS_VPR_MAP_SCALE_BENCHMARK_PATH, "--data nowhere", "--sizes"},
          {"mrs_vpr_debug_image_benchmark", MRS_VPR_DEBUG_IMAGE_BENCHMARK_PATH, "--reference nowhere --query nowhere",
           "--lengths"}};
}

/// Expects exit code 1 and one line on stderr, "<name>: error: ...", that contains `text`.
void expectBenchmarkError(const Benchmark& benchmark, const Result& result, const std::string& text) {
  EXPECT_EQ(result.status, 1) << benchmark.name << "\n" << result.err;
  EXPECT_EQ(result.err.rfind(benchmark.name + ": error: ", 0), 0U) << result.err;
  EXPECT_NE(result.err.find(text), std::string::npos) << benchmark.name << "\n" << result.err;
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  EXPECT_EQ(result.out, "") << benchmark.name;
}

TEST_F(ToolsTest, BenchmarksPrintTheirUsageOnHelp) {
  for (const Benchmark& benchmark : benchmarks()) {
    for (const char* help : {" --help", " -h"}) {
      const Result result = run(benchmark.path + help);
      EXPECT_EQ(result.status, 0) << benchmark.name << help << "\n" << result.err;
      EXPECT_EQ(result.out.rfind("Usage: " + benchmark.name + " ", 0), 0U) << result.out;
      // Every option is listed with its default, lists as they are written.
      EXPECT_NE(result.out.find("\nOptions:\n"), std::string::npos) << result.out;
      EXPECT_NE(result.out.find(benchmark.list_option + " arg (="), std::string::npos) << result.out;
      EXPECT_EQ(result.err, "") << benchmark.name;
    }
  }
  EXPECT_NE(run(std::string(MRS_VPR_BENCHMARK_PATH) + " --help").out.find("--threads arg (=1,2)"), std::string::npos);
  EXPECT_NE(run(std::string(MRS_VPR_REAL_BENCHMARK_PATH) + " --help").out.find("--lengths arg (=100,200,300)"),
            std::string::npos);
  EXPECT_NE(run(std::string(MRS_VPR_MAP_SCALE_BENCHMARK_PATH) + " --help").out.find("--sizes arg (=10k,100k,1M)"),
            std::string::npos);
}

TEST_F(ToolsTest, BenchmarksRefuseBadOptionsInOneLineNamingThem) {
  for (const Benchmark& benchmark : benchmarks()) {
    const std::string command = benchmark.path + " " + benchmark.required;
    expectBenchmarkError(benchmark, run(command + " --no-such-option 3"), "unrecognised option '--no-such-option'");
    expectBenchmarkError(benchmark, run(command + " --queries"), "option '--queries' is missing");
    expectBenchmarkError(benchmark, run(command + " --queries many"),
                         "the argument ('many') for option '--queries' is invalid");
    // A list with a bad, empty or trailing item is refused whole.
    for (const std::string list : {"10,x", "10,,20", "10,"}) {
      const Result result = run(command + " " + benchmark.list_option + " " + list);
      if (benchmark.list_option == "--sizes") {  // Items are sizes such as 10k, checked one by one.
        expectBenchmarkError(benchmark, result, "--sizes");
      } else {
        expectBenchmarkError(benchmark, result,
                             "the argument ('" + list + "') for option '" + benchmark.list_option + "' is invalid");
      }
    }
    // A word that belongs to no option ("--lengths 100 200" for "100,200") is not dropped silently.
    expectBenchmarkError(benchmark, run(command + " " + benchmark.list_option + " 10 20"), "unexpected argument '20'");
  }
  const Benchmark real = benchmarks()[1];
  expectBenchmarkError(real, run(real.path + " --queries 2"), "the option '--data' is required but missing");
  expectBenchmarkError(real, run(real.path + " --data nowhere --part most"), "--part must be tune, check or all");
  expectBenchmarkError(real, run(real.path + " --data nowhere --references 1.8k,5k"), "--references takes 1.8k");
  expectBenchmarkError(real, run(real.path + " --data nowhere --methods mrs,fastest"), "unknown method 'fastest'");
  expectBenchmarkError(real, run(real.path + " --data nowhere --seed -1"), "--seed must be >= 0");
  const Benchmark scale = benchmarks()[2];
  expectBenchmarkError(scale, run(scale.path + " --data nowhere --sizes 10k,lots"), "bad size 'lots'");
  expectBenchmarkError(scale, run(scale.path + " --data nowhere --sizes 1k"), "bad size '1k'");
  const Benchmark debug = benchmarks()[3];
  expectBenchmarkError(debug, run(debug.path + " --reference nowhere"), "the option '--query' is required but missing");
  expectBenchmarkError(debug, run(debug.path + " --reference a --query b --picture-method best"),
                       "--picture-method must be mrs or seqslam");
  const Benchmark search = benchmarks()[0];
  expectBenchmarkError(search, run(search.path + " --threads 1,0"), "--threads takes counts >= 1");
  expectBenchmarkError(search, run(search.path + " --reference-frames 600 --sequence-length 600"),
                       "--sequence-length must be in 2..490");
}

TEST_F(ToolsTest, TheGeneratedRouteBenchmarkRunsWithTheGivenOptions) {
  const Result result = run(std::string(MRS_VPR_BENCHMARK_PATH) +
                            " --reference-frames 600 --sequence-length 20 --queries 3 --threads 1 --min-time 0"
                            " --tolerance 4 --seed 3 --velocity-step 0.1");
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_NE(result.out.find("the same 3 queries (synthetic route, seed 3)"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("M = 600 reference frames, N = 20 frame test sequences, velocity step 0.10, "
                            "success = within 4 frames"),
            std::string::npos)
      << result.out;
  // One thread count: its two rows and its speed-up, and no second block.
  EXPECT_NE(result.out.find("\n1        seqslam "), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("\n1        mrs "), std::string::npos) << result.out;
  EXPECT_EQ(result.out.find("\n2        "), std::string::npos) << result.out;

  // Success is judged at the frame an answer localises (the middle one at the default alignment): on
  // the generated route both methods find every place of 60-frame sequences.
  const Result judged = run(std::string(MRS_VPR_BENCHMARK_PATH) +
                            " --reference-frames 600 --sequence-length 60 --queries 5 --threads 1 --min-time 0");
  ASSERT_EQ(judged.status, 0) << judged.err;
  EXPECT_NE(judged.out.find("\n1        seqslam     1.000 "), std::string::npos) << judged.out;
  EXPECT_NE(judged.out.find("\n1        mrs         1.000 "), std::string::npos) << judged.out;
}

TEST_F(ToolsTest, TheDebugImageBenchmarkRunsWithTheGivenOptions) {
  const std::string picture = path("debug_image.png");
  const Result result = run(std::string(MRS_VPR_DEBUG_IMAGE_BENCHMARK_PATH) + " --reference " + path("reference") +
                            " --query " + path("query") +
                            " --lengths 10,20 --queries 2 --runs 1 --methods seqslam --threads 1 --output " + picture +
                            " --picture-length 20 --picture-end 30 --picture-method seqslam");
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_NE(result.out.find("reference 150 frames, query 100 frames, 1 thread(s), 2 queries per row"),
            std::string::npos)
      << result.out;
  EXPECT_NE(result.out.find("\nseqslam     10 |"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("\nseqslam     20 |"), std::string::npos) << result.out;
  EXPECT_EQ(result.out.find("\nmrs "), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("query frames 11..30, seqslam"), std::string::npos) << result.out;
  EXPECT_FALSE(cv::imread(picture).empty());
}

/// The generated route in the layout of the real data (nordland/{summer,winter}, corridor/{ref,query}):
/// the reference as summer and as the corridor's reference, the query as winter and the corridor's query.
fs::path realDataLayout(const fs::path& root) {
  const fs::path data = root / "real_data";
  if (fs::exists(data)) return data;
  fs::create_directories(data / "nordland");
  fs::create_directories(data / "corridor");
  fs::create_directory_symlink(root / "reference", data / "nordland" / "summer");
  fs::create_directory_symlink(root / "query", data / "nordland" / "winter");
  fs::create_directory_symlink(root / "reference", data / "corridor" / "ref");
  fs::create_directory_symlink(root / "query", data / "corridor" / "query");
  return data;
}

TEST_F(ToolsTest, TheRealDataBenchmarkRunsWithTheGivenOptions) {
  const fs::path data = realDataLayout(path(""));
  const std::string output = path("real_benchmark.json");
  const Result result =
      run(std::string(MRS_VPR_REAL_BENCHMARK_PATH) + " --data " + data.string() +
          " --part all --references 1.8k --lengths 20,30 --queries 3 --methods seqslam --skip-per-frame --skip-drives"
          " --tolerance 4 --seed 5 --json " +
          output);
  ASSERT_EQ(result.status, 0) << result.err;
  const json document = json::parse(readText(output));
  EXPECT_EQ(document.at("part"), "all");
  EXPECT_EQ(document.at("queries"), 3);
  EXPECT_EQ(document.at("tolerance"), 4);
  EXPECT_EQ(document.at("seed"), 5);
  // Global rows only, one per length, of seqslam alone; --part all has no out-of-map rows. First the
  // route's map, then the four replays (backwards, twice and half the speed, stops) in the whole
  // summer map.
  const json& rows = document.at("rows");
  ASSERT_EQ(rows.size(), 2U + 4U * 2U) << rows.dump();
  const std::vector<std::string> replays = {"backwards", "at twice the speed", "at half the speed", "with stops"};
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i].at("method"), "seqslam");
    EXPECT_EQ(rows[i].at("protocol"), "global");
    EXPECT_EQ(rows[i].at("out_of_map"), false);
    const int length = i % 2 == 0 ? 20 : 30;
    EXPECT_EQ(rows[i].at("sequence_length"), length);
    EXPECT_EQ(rows[i].at("summary").at("queries"), 3);
    // A number when an accepted answer was wrong, else null.
    const json& wrong_error = rows[i].at("summary").at("largest_wrong_accepted_error");
    const double precision = rows[i].at("summary").at("accepted_precision").is_null()
                                 ? 1.0
                                 : rows[i].at("summary").at("accepted_precision").get<double>();
    EXPECT_EQ(wrong_error.is_null(), precision == 1.0) << rows[i].dump();
    if (i < 2) {
      EXPECT_EQ(rows[i].at("reference_frames"), 100);  // The route: as many summer frames as there are winter ones.
    } else {
      EXPECT_EQ(rows[i].at("reference_frames"), 150);  // Every summer frame.
      EXPECT_EQ(rows[i].at("setting"), "global winter " + replays[(i - 2) / 2] + " N=" + std::to_string(length) +
                                           " M=150");
    }
  }
}

/// The real-data benchmark's camera-drive rows alone (seeds 5 and 6, brute force), with `options`,
/// written as JSON to `output`.
std::string cameraDrivesCommand(const fs::path& data, const std::string& options, const std::string& output) {
  return std::string(MRS_VPR_REAL_BENCHMARK_PATH) + " --data " + data.string() +
         " --part all --references 1.8k --methods seqslam --skip-per-frame --skip-global --seed 5" + options +
         " --json " + output;
}

TEST_F(ToolsTest, TheRealDataBenchmarkReplaysCameraDrivesThroughContinuousModeAndTheEvaluator) {
  const fs::path data = realDataLayout(path(""));
  const std::string output = path("real_benchmark_drives.json");
  const Result result = run(cameraDrivesCommand(data, "", output));
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_NE(result.out.find("Camera drives (make_drive --seed 5 and 6)"), std::string::npos) << result.out;
  const json rows = json::parse(readText(output)).at("rows");
  // Besides the replays' rows (none here: no global, no per-frame rows): the map drive and the revisit
  // in continuous mode, then the evaluator's per-frame protocol on the two drives.
  ASSERT_EQ(rows.size(), 3U) << rows.dump();
  for (std::size_t i = 0; i < 2; ++i) {
    const json& row = rows[i];
    EXPECT_EQ(row.at("protocol"), "continuous");
    EXPECT_EQ(row.at("method"), "seqslam");
    // Continuous mode's length is the node's: auto_query_frames 0, so sequence/sequence_length.
    EXPECT_EQ(row.at("sequence_length"), mrs_vpr::SequenceParams{}.sequence_length);
    const json& drive = row.at("drive");
    EXPECT_EQ(drive.at("route_begin"), 0);
    EXPECT_EQ(drive.at("route_end"), 100);  // The route: as many summer frames as there are winter ones.
    EXPECT_EQ(drive.at("rate_hz"), i == 0 ? 30.0 : 10.0);
    EXPECT_GE(drive.at("stopped_frames").get<int>(), 8 * 30);
    EXPECT_LE(drive.at("stopped_frames").get<int>(), 8 * 90);
    // Stops add (almost) no keyframes.
    EXPECT_LT(row.at("stopped_keyframes").get<int>(), drive.at("stopped_frames").get<int>() / 10);
    EXPECT_EQ(row.at("accepted").get<int>(), row.at("accepted_right").get<int>() + row.at("accepted_wrong").get<int>());
    for (const char* field : {"keyframes", "queries", "stretches", "stretches_keyframed", "stretches_with_right"}) {
      EXPECT_TRUE(row.contains(field)) << field;
    }
  }
  EXPECT_EQ(rows[0].at("setting"), "camera drive continuous map drive");
  EXPECT_EQ(rows[0].at("accepted_right"), 0);  // No place comes back on the first traversal.
  // How far the wrong closures lie is measured on revisits only. A wrong one lies beyond the tolerance
  // of 2 places, and so beyond 2 route frames (a place is one route frame or more); with none, 0.
  for (const char* unit : {"largest_wrong_error_places", "largest_wrong_error_route_frames"}) {
    EXPECT_EQ(rows[0].at(unit), 0) << unit;
    const int revisit_wrong = rows[1].at("accepted_wrong").get<int>() + rows[1].at("restated_wrong").get<int>();
    const int largest_error = rows[1].at(unit).get<int>();
    if (revisit_wrong > 0) {
      EXPECT_GT(largest_error, 2) << unit << " " << rows[1].dump();
    } else {
      EXPECT_EQ(largest_error, 0) << unit << " " << rows[1].dump();
    }
  }
  EXPECT_LE(rows[1].at("largest_wrong_error_places").get<int>(), rows[1].at("largest_wrong_error_route_frames").get<int>());
  EXPECT_EQ(rows[1].at("setting"), "camera drive continuous revisit");
  EXPECT_EQ(rows[2].at("setting"), "camera drives per-frame (mrs_vpr_eval)");
  EXPECT_EQ(rows[2].at("protocol"), "per-frame");
  EXPECT_GT(rows[2].at("summary").at("queries").get<int>(), 0);
}

TEST_F(ToolsTest, TheRealDataBenchmarksDrivesKeyframeAtTheThresholdGiven) {
  const fs::path data = realDataLayout(path(""));
  const std::string output = path("real_benchmark_every_frame.json");
  const Result result = run(cameraDrivesCommand(data, " --drive-min-appearance-change 0", output));
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_NE(result.out.find("keyframes by appearance change 0.00"), std::string::npos) << result.out;
  const json rows = json::parse(readText(output)).at("rows");
  ASSERT_EQ(rows.size(), 3U) << rows.dump();
  // At 0 every frame is a keyframe, stopped ones included (at the default, stops add almost none).
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(rows[i].at("stopped_keyframes"), rows[i].at("drive").at("stopped_frames")) << rows[i].dump();
  }
}

TEST_F(ToolsTest, TheRealDataBenchmarksDrivesAcceptAtTheThresholdGiven) {
  const fs::path data = realDataLayout(path(""));
  const std::string output = path("real_benchmark_threshold.json");
  // No confidence reaches 1000: nothing is accepted, on either drive.
  const Result result = run(cameraDrivesCommand(data, " --drive-accept-threshold 1000", output));
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_NE(result.out.find("accepted at confidence 1000.0"), std::string::npos) << result.out;
  const json rows = json::parse(readText(output)).at("rows");
  ASSERT_EQ(rows.size(), 3U) << rows.dump();
  for (std::size_t i = 0; i < 2; ++i) EXPECT_EQ(rows[i].at("accepted"), 0) << rows[i].dump();
  EXPECT_EQ(rows[2].at("summary").at("accepted"), 0) << rows[2].dump();
  const Result refused = run(cameraDrivesCommand(data, " --drive-accept-threshold -1", output));
  EXPECT_NE(refused.status, 0);
  EXPECT_EQ(refused.out.find("Camera drives"), std::string::npos) << "refused before any drive: " << refused.out;
  EXPECT_NE(refused.err.find("sequence/accept_threshold must be in 0..1000, got -1"), std::string::npos) << refused.err;
}

TEST_F(ToolsTest, TheRealDataBenchmarkListsTheStretchesNoClosureConfirmed) {
  const fs::path data = realDataLayout(path(""));
  const std::string output = path("real_benchmark_missed.json");
  // Nothing is accepted at 1000: every stretch of the revisit is missed, and listed with its answers
  // (every frame a keyframe, so that this short route is asked about).
  const Result result = run("MRS_VPR_SHOW_MISSED=1 " +
                            cameraDrivesCommand(data, " --drive-accept-threshold 1000 --drive-min-appearance-change 0",
                                                output));
  ASSERT_EQ(result.status, 0) << result.err;
  const json revisit = json::parse(readText(output)).at("rows").at(1);
  ASSERT_EQ(revisit.at("setting"), "camera drive continuous revisit");
  int listed = 0;
  int with_answers = 0;
  std::istringstream lines(result.err);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("missed stretch: revisit", 0) != 0) continue;
    ++listed;
    // An answer: the localised route frame, its confidence, and x when it would have been wrong.
    with_answers += line.find(":", line.find("answers:") + 8) != std::string::npos ? 1 : 0;
  }
  EXPECT_EQ(listed, revisit.at("stretches").get<int>()) << result.err;
  ASSERT_GT(revisit.at("queries").get<int>(), 0) << revisit.dump();
  EXPECT_GT(with_answers, 0) << result.err;
  EXPECT_EQ(result.err.find("missed stretch: map drive"), std::string::npos) << "only revisits are listed";
}

TEST_F(ToolsTest, TheRealDataBenchmarkRefusesBadDriveSettingsBeforeReadingFrames) {
  // "nowhere" holds no frames: each refusal names the setting, not the missing data.
  const std::string command = std::string(MRS_VPR_REAL_BENCHMARK_PATH) + " --data " + path("nowhere");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {" --drive-queries all", "--drive-queries must be newest or each, got 'all'"},
      {" --drive-seeds 0", "--drive-seeds must be >= 1, got 0"},
      {" --drive-alignment ahead", "sequence/alignment must be one of causal, centred, got 'ahead'"},
      {" --drive-length 1", "sequence/sequence_length"},
      {" --drive-alignment-slack -1", "sequence/alignment_slack"}};
  for (const auto& [options, message] : cases) {
    const Result refused = run(command + options);
    EXPECT_NE(refused.status, 0) << options;
    EXPECT_NE(refused.err.find(message), std::string::npos) << options << ": " << refused.err;
    EXPECT_EQ(refused.err.find("nowhere"), std::string::npos) << options << ": " << refused.err;
  }
}

TEST_F(ToolsTest, TheRealDataBenchmarksDrivesLeaveOutTheFirstPassAlone) {
  // mrs-first-pass is a search of the global and per-frame rows, not a method of the node: the drives
  // run the other methods and say so, instead of failing after every other row.
  const fs::path data = realDataLayout(path(""));
  const std::string output = path("real_benchmark_first_pass.json");
  const Result result = run(std::string(MRS_VPR_REAL_BENCHMARK_PATH) + " --data " + data.string() +
                            " --part all --references 1.8k --methods seqslam,mrs-first-pass --skip-per-frame"
                            " --skip-global --seed 5 --json " + output);
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_NE(result.err.find("mrs-first-pass is not a method of the node"), std::string::npos) << result.err;
  const json rows = json::parse(readText(output)).at("rows");
  ASSERT_EQ(rows.size(), 3U) << rows.dump();
  for (const json& row : rows) EXPECT_EQ(row.at("method"), "seqslam") << row.dump();
}

TEST_F(ToolsTest, TheMapScaleBenchmarkRunsWithTheGivenOptions) {
  const fs::path data = realDataLayout(path(""));
  const fs::path maps = path("maps");
  const Result result = run(std::string(MRS_VPR_MAP_SCALE_BENCHMARK_PATH) + " --data " + data.string() +
                            " --sizes 2k,2.5k --dir " + maps.string() +
                            " --lengths 10 --queries 2 --brute-queries 1 --threads 1 --periods 2"
                            " --keyframes-per-period 1 --seed 4");
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_NE(result.out.find("queries of N = 10, 2 per map (1 for brute force), threads 1, seed 4"), std::string::npos)
      << result.out;
  // Each map is measured by a child process that gets the options again: one row per map and kind of
  // query, with 2 queries of mrs and 1 of brute force.
  for (const std::string size : {"2k", "2500"}) {
    EXPECT_TRUE(fs::exists(maps / ("map-" + size + "-hog-seed4.db"))) << size;
    for (const std::string kind : {"winter", "summer*"}) {
      std::istringstream lines(result.out);
      std::vector<std::string> row;
      for (std::string line; std::getline(lines, line);) {
        std::istringstream words(line);
        std::vector<std::string> tokens{std::istream_iterator<std::string>(words), {}};
        if (tokens.size() == 14 && tokens[0] == size && tokens[1] == "10" && tokens[2] == kind) row = tokens;
      }
      ASSERT_EQ(row.size(), 14U) << size << " " << kind << "\n" << result.out;
      EXPECT_EQ(row[8].substr(row[8].find('/')), "/2") << row[8];   // mrs right
      EXPECT_EQ(row[10].substr(row[10].find('/')), "/1") << row[10];  // brute force right
      EXPECT_EQ(row[12].substr(row[12].rfind('/')), "/1") << row[12];  // same frame / acceptance, of 1
    }
  }
  // Questions about the newest frames, with rows kept (after a new keyframe, and again with none) and
  // without: both methods answered.
  for (const std::string kind : {"recent", "recent=", "recent*"}) {
    int rows = 0;
    std::istringstream lines(result.out);
    for (std::string line; std::getline(lines, line);) {
      std::istringstream words(line);
      const std::vector<std::string> tokens{std::istream_iterator<std::string>(words), {}};
      if (tokens.size() == 14 && tokens[1] == "10" && tokens[2] == kind) {
        ++rows;
        EXPECT_EQ(tokens[12].substr(tokens[12].rfind('/')), "/1") << line;  // both methods answered one
        // From kept rows MRS gives the brute force's frame and acceptance.
        if (kind == "recent=") EXPECT_EQ(tokens[12], "1/1/1") << line;
      }
    }
    EXPECT_EQ(rows, 2) << kind << " (one a map)\n" << result.out;
  }
  // Continuous mode: one row a method, its queries' CPU share at a 1 s period.
  EXPECT_NE(result.out.find("mrs continuous mode: 1 keyframes a period"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("seqslam continuous mode: 1 keyframes a period"), std::string::npos) << result.out;
  // How fast the machine streams each map: the cost of a new keyframe's row, which bounds the rows' speed-up.
  for (const std::string size : {"2k", "2500"}) {
    EXPECT_NE(result.out.find(size + "  map stream: one keyframe against every map frame (a new keyframe's row), median of 7: "),
              std::string::npos)
        << size << "\n" << result.out;
  }
}

}  // namespace
