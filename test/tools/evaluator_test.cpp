// mrs_vpr_eval run as a user runs it on a generated route: its protocols, the records and summary it
// writes, its acceptance options, and one-line errors with exit code 1 on bad input.

#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "mrs_vpr/acceptance.hpp"
#include "mrs_vpr/parameters.hpp"
#include "route_tools_fixture.hpp"
#include "support/format_one_map.hpp"

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using mrs_vpr::testing_support::CommandResult;
using mrs_vpr::testing_support::fileContents;

class EvaluatorTest : public mrs_vpr::testing_support::RouteToolsTest {};

TEST_F(EvaluatorTest, PerFrameSeqSlamFindsThePlantedAlignment) {
  const std::string output = path("per_frame.json");
  const CommandResult result = run(
      eval("--reference " + path("reference") + " --query " + path("query") + " --ground-truth " + path("truth.csv") +
           " --method seqslam --protocol per-frame --sequence-length 10 --alignment causal --tolerance 2 --output " +
           output));
  ASSERT_EQ(result.status, 0) << result.err;
  const json document = json::parse(fileContents(output));
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

TEST_F(EvaluatorTest, GlobalProtocolIsSeededAndUsesKSequences) {
  const std::string arguments = "--reference " + path("reference") + " --query " + path("query") + " --ground-truth " +
                                path("truth.csv") +
                                " --method seqslam --protocol global --sequence-length 40 --alignment causal " +
                                "--queries 12 --tolerance 5 --seed 3 --output ";
  ASSERT_EQ(run(eval(arguments + path("global_a.json"))).status, 0);
  ASSERT_EQ(run(eval(arguments + path("global_b.json"))).status, 0);
  const json a = json::parse(fileContents(path("global_a.json")));
  const json b = json::parse(fileContents(path("global_b.json")));
  ASSERT_EQ(a.at("records").size(), 12U);
  for (std::size_t i = 0; i < 12; ++i) {
    EXPECT_EQ(a["records"][i]["query_index"], b["records"][i]["query_index"]);
    EXPECT_GE(a["records"][i]["query_index"].get<int>(), 39);
  }
  EXPECT_GE(a.at("summary").at("top1").get<double>(), 0.9);
  // More test sequences than the query has positions for: said, as the summary counts the repeats.
  const CommandResult more = run(eval("--reference " + path("reference") + " --query " + path("query") +
                                      " --method seqslam --protocol global --sequence-length 90 --queries 50"));
  ASSERT_EQ(more.status, 0) << more.err;
  EXPECT_NE(more.err.find("50 test sequences, but the query has "), std::string::npos) << more.err;
  EXPECT_NE(more.err.find("(the summary counts every test sequence)"), std::string::npos) << more.err;
}

TEST_F(EvaluatorTest, BadInputGivesOneLineAndExitCodeOne) {
  const std::string folders = "--reference " + path("reference") + " --query " + path("query");
  expectError("--reference " + path("nowhere") + " --query " + path("query") +
                  " --method seqslam --protocol per-frame --sequence-length 10",
              "image folder '" + path("nowhere") + "' does not exist");
  // A mistyped query is named before the reference is described.
  const CommandResult no_query = run(eval("--reference " + path("reference") + " --query " + path("nowhere") +
                                          " --protocol per-frame"));
  EXPECT_EQ(no_query.status, 1);
  EXPECT_NE(no_query.err.find("image folder '" + path("nowhere") + "' does not exist"), std::string::npos)
      << no_query.err;
  EXPECT_EQ(no_query.err.find("reference:"), std::string::npos) << "work was done first: " << no_query.err;
  expectError(folders + " --method fastest --protocol per-frame --sequence-length 10", "unknown method 'fastest'");
  expectError(folders + " --method mrs --protocol sideways --sequence-length 10", "unknown protocol 'sideways'");
  expectError(folders + " --method seqslam --protocol global --sequence-length 151",
              "sequence length 151 is larger than the reference of 150 keyframes");
  expectError(folders + " --method seqslam --sequence-length 10", "protocol");  // Missing flag.
  expectError(folders + " --method seqslam --protocol per-frame --sequence-length 10 --ground-truth " + path("query"),
              "ground-truth file '" + path("query") + "' is a folder (give the CSV file)");
  // An option of the front end not in use is refused, not ignored.
  const CommandResult thumbnail_option =
      run(std::string(MRS_VPR_EVAL_PATH) + " " + folders + " --protocol per-frame --image-width 16");
  EXPECT_EQ(thumbnail_option.status, 1);
  EXPECT_NE(thumbnail_option.err.find("--image-width is an option of the thumbnail front end, and the front end is "
                                      "hog (add --descriptor thumbnail)"),
            std::string::npos)
      << thumbnail_option.err;
  expectError(folders + " --method seqslam --protocol per-frame --sequence-length 10 --hog-cell-size 8",
              "--hog-cell-size is an option of the hog front end, and the front end is thumbnail");
  // An unset shell variable is no option left out: not the identity ground truth, not a JSON unwritten.
  for (const char* option : {"--ground-truth", "--output", "--plots"}) {
    expectError(folders + " --method seqslam --protocol per-frame --sequence-length 10 " + option + " ''",
                std::string(option) + " was given an empty path");
  }
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

TEST_F(EvaluatorTest, AMapDatabaseIsKnownByItsContentsAndRefusedAsTheQuery) {
  const std::string map = path("named_otherwise.sqlite");
  ASSERT_EQ(run(buildMap() + " --images " + path("reference") + " --output " + map).status, 0);
  const std::string arguments = " --protocol per-frame --sequence-length 10 --method seqslam";
  // Read as the map it is, not as an image folder it is not.
  const CommandResult as_reference = run(eval("--reference " + map + " --query " + path("query") + arguments));
  EXPECT_EQ(as_reference.status, 0) << as_reference.err;
  EXPECT_NE(as_reference.err.find("keyframes from the map database " + map), std::string::npos) << as_reference.err;
  expectError("--reference " + path("reference") + " --query " + map + arguments,
              "--query '" + map + "' is a map database (named *.db or an SQLite file), which holds a map's "
              "keyframes; the query is a traversal to keyframe and match: a folder of images or a bag");
  // A folder of images named as a database is a folder; a missing one is named as missing.
  fs::create_directories(path("frames.DB"));
  for (int i = 0; i < 30; ++i) {
    fs::create_symlink(path("query/00050.png"), path("frames.DB/" + std::to_string(1000 + i) + ".png"));
  }
  const CommandResult folder = run(eval("--reference " + path("frames.DB") + " --query " + path("query") + arguments));
  EXPECT_EQ(folder.status, 0) << folder.err;
  expectError("--reference " + path("reference") + " --query " + path("nothing_here.db") + arguments,
              "image folder '" + path("nothing_here.db") + "' does not exist");
}

// A node's map holds a stretch once per visit, with the loop closures that linked the visits: the
// evaluator judges its answers with the links, as the node does, and without them the twin visits are
// each other's rivals.
TEST_F(EvaluatorTest, AMapDatabaseIsJudgedWithItsPlaceLinks) {
  const std::string once = path("route_once.db");
  const std::string twice = path("route_twice.db");
  ASSERT_EQ(run(buildMap() + " --images " + path("reference") + " --output " + once).status, 0);
  ASSERT_EQ(run(buildMap() + " --images " + path("reference") + " --output " + twice).status, 0);
  // Appended without links: the links below stand for the closures that would have linked the visits.
  const std::string unlinked_append = " --append --no-place-links";
  ASSERT_EQ(run(buildMap() + " --images " + path("reference") + " --output " + twice + unlinked_append).status, 0);
  const auto accepted = [&](const std::string& map, const std::string& output) {
    const CommandResult result =
        run(eval("--reference " + map + " --query " + path("query") + " --ground-truth " + path("truth.csv") +
                 " --method seqslam --protocol per-frame --sequence-length 20 --tolerance 2 --accept-threshold 2.5" +
                 " --output " + output));
    EXPECT_EQ(result.status, 0) << result.err;
    return std::make_pair(json::parse(fileContents(output)).at("summary").at("accepted").get<int>(), result.err);
  };
  const int of_one_visit = accepted(once, path("once.json")).first;
  const int unlinked = accepted(twice, path("twice.json")).first;
  EXPECT_GT(of_one_visit, 5);
  EXPECT_LT(unlinked, of_one_visit / 2) << unlinked;
  // Each frame of the second visit linked to the first's, as accepted closures would have linked them.
  const int frames =
      static_cast<int>(std::distance(fs::directory_iterator(path("reference")), fs::directory_iterator()));
  mrs_vpr::testing_support::runSql(twice, "WITH RECURSIVE i(n) AS (SELECT 0 UNION ALL SELECT n + 1 FROM i WHERE n < " +
                                              std::to_string(frames - 1) +
                                              ") INSERT INTO place_links (frame, reference) SELECT n + " +
                                              std::to_string(frames) + ", n FROM i");
  const auto [linked, progress] = accepted(twice, path("linked.json"));
  // The twin is no rival, and the map's other places count twice among the rivals, which on a map of
  // a few dozen places lowers the required confidence (requiredConfidence()): at least as many.
  EXPECT_GE(linked, of_one_visit);
  EXPECT_NE(progress.find(std::to_string(frames) + " of them linked by its loop closures"), std::string::npos)
      << progress;
}

TEST_F(EvaluatorTest, AQueryOfTooFewKeyframesSaysSo) {
  // One view shown again and again: a robot standing still, whose frames keyframing keeps one of.
  fs::create_directories(path("standing"));
  for (int i = 0; i < 30; ++i) {
    fs::create_symlink(path("query/00050.png"), path("standing/" + std::to_string(1000 + i) + ".png"));
  }
  for (const char* protocol : {"per-frame", "global"}) {
    const CommandResult result =
        run(std::string(MRS_VPR_EVAL_PATH) + " --descriptor thumbnail --reference " + path("reference") +
            " --query " + path("standing") + " --sequence-length 10 --protocol " + protocol);
    EXPECT_EQ(result.status, 1) << result.err;
    EXPECT_NE(result.err.find("the query's 30 frames hold 1 keyframes, fewer than the sequence length 10: its view "
                              "hardly changes (a stop), or --min-appearance-change is too high for these frames (0 "
                              "keeps every frame)"),
              std::string::npos)
        << result.err;
  }
}

TEST_F(EvaluatorTest, AMapTooSmallForTheAcceptanceRuleIsNamed) {
  // 40 places: too few trajectory ends outside an answer's window for a confidence, so none is accepted
  // and there is no PR curve; the tool says why rather than leave it to look like a method that fails.
  fs::create_directories(path("small_map"));
  for (int i = 0; i < 40; ++i) {
    char name[16];
    std::snprintf(name, sizeof(name), "%05d.png", i);
    fs::create_symlink(path(std::string("reference/") + name), path(std::string("small_map/") + name));
  }
  const CommandResult result = run(eval("--reference " + path("small_map") + " --query " + path("query") +
                                        " --protocol per-frame --sequence-length 10 --method seqslam"));
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_EQ(json::parse(result.out).at("summary").at("accepted").get<int>(), 0);
  EXPECT_NE(result.err.find("trajectory ends outside their window in the map of 40 keyframes: the acceptance rule "
                            "gives them confidence 0 and accepts none of them; every confidence is equal, so there is "
                            "no PR curve"),
            std::string::npos)
      << result.err;
  // The whole route's map says nothing of it.
  const CommandResult whole = run(eval("--reference " + path("reference") + " --query " + path("query") +
                                       " --protocol per-frame --sequence-length 10 --method seqslam"));
  ASSERT_EQ(whole.status, 0) << whole.err;
  EXPECT_EQ(whole.err.find("trajectory ends outside"), std::string::npos) << whole.err;
}

/// Records of `records` whose boolean `field` is true.
int countTrue(const json& records, const char* field) {
  int count = 0;
  for (const json& record : records) count += record.at(field).get<bool>() ? 1 : 0;
  return count;
}

TEST_F(EvaluatorTest, RecordsCarryTheAcceptanceRuleAndTheSummaryCountsIt) {
  const std::string arguments = "--reference " + path("reference") + " --query " + path("query") + " --ground-truth " +
                                path("truth.csv") + " --method seqslam --protocol per-frame --sequence-length 20 " +
                                "--tolerance 2 --accept-threshold 2.5 --output ";
  ASSERT_EQ(run(eval(arguments + path("accept_rule.json"))).status, 0);
  const json document = json::parse(fileContents(path("accept_rule.json")));
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

TEST_F(EvaluatorTest, AcceptThresholdZeroAcceptsEveryAnswerAndAThousandNone) {
  const std::string arguments = "--reference " + path("reference") + " --query " + path("query") + " --ground-truth " +
                                path("truth.csv") + " --method seqslam --protocol per-frame --sequence-length 10 " +
                                "--tolerance 2 --output ";
  ASSERT_EQ(run(eval(arguments + path("accept_all.json") + " --accept-threshold 0")).status, 0);
  ASSERT_EQ(run(eval(arguments + path("accept_none.json") + " --accept-threshold 1000")).status, 0);
  const json all = json::parse(fileContents(path("accept_all.json")));
  const json none = json::parse(fileContents(path("accept_none.json")));
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

TEST_F(EvaluatorTest, OutOfMapQueriesHaveNoTrueIndexAndEveryAcceptedAnswerIsFalse) {
  const std::string arguments = "--reference " + path("reference") + " --query " + path("query") +
                                " --out-of-map --method seqslam --protocol per-frame --sequence-length 20 --output ";
  // At the default threshold, and at 0 where every answer is accepted (the route's query is in fact
  // in the map, so only --out-of-map makes them false).
  for (const std::string threshold : {"3", "0"}) {
    const std::string output = path("out_of_map_" + threshold + ".json");
    const CommandResult result = run(eval(arguments + output + " --accept-threshold " + threshold));
    ASSERT_EQ(result.status, 0) << result.err;
    const json document = json::parse(fileContents(output));
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
    // No query has a right answer: top-1 and the recalls mean nothing, and say so.
    EXPECT_EQ(summary.at("queries_in_map").get<int>(), 0) << threshold;
    for (const char* figure : {"top1", "pr_auc", "recall_at_100_precision", "accepted_recall"}) {
      EXPECT_TRUE(summary.at(figure).is_null()) << figure << ": " << summary;
    }
    if (accepted == 0) {
      EXPECT_TRUE(summary.at("accepted_precision").is_null()) << summary;
    } else {
      EXPECT_DOUBLE_EQ(summary.at("accepted_precision").get<double>(), 0.0) << summary;
    }
    if (threshold == "0") EXPECT_EQ(accepted, 81);
  }
}

TEST_F(EvaluatorTest, AcceptanceOptionsAreChecked) {
  const std::string folders = "--reference " + path("reference") + " --query " + path("query") +
                              " --method seqslam --protocol per-frame --sequence-length 10";
  // A query cannot be both outside the map and have a true place in it.
  expectError(folders + " --out-of-map --ground-truth " + path("truth.csv"),
              "--out-of-map and --ground-truth exclude each other");
  expectError(folders + " --threads -1", "--threads must be in 0..1024");
  expectError(folders + " --threads 100000", "--threads must be in 0..1024");  // Crashed at exit before.
  expectError(folders + " --queries 1000000", "--queries must be in 1..100000");
  expectError(folders + " --queries 0", "--queries must be in 1..100000");  // a global protocol of no test sequence
  expectError(folders + " --accept-threshold -1", "sequence/accept_threshold");
  expectError(folders + " --accept-threshold 1001", "sequence/accept_threshold");
  // Nothing is written for rejected options.
  EXPECT_FALSE(fs::exists(path("rejected.json")));
  expectError(folders + " --threads -1 --output " + path("rejected.json"), "--threads must be in 0..1024");
  EXPECT_FALSE(fs::exists(path("rejected.json")));
}

TEST_F(EvaluatorTest, BadSeedAndGroundTruthOfOtherTraversalsAreRefused) {
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
  // Refused before a single image is described, which takes minutes on a long traversal.
  const CommandResult beyond = run(eval(folders + " --ground-truth " + path("beyond.csv")));
  EXPECT_EQ(beyond.err.find("described"), std::string::npos) << beyond.err;
  EXPECT_EQ(beyond.err.find("reference:"), std::string::npos) << beyond.err;
  {
    std::ofstream huge(path("huge.csv"));
    huge << "query_index,matching_ref_indices\n0,999999999\n";
  }
  expectError(folders + " --ground-truth " + path("huge.csv"), "reference frame 999999999");
}

TEST_F(EvaluatorTest, ThreadCountDoesNotChangeTheAnswers) {
  const std::string arguments = "--reference " + path("reference") + " --query " + path("query") + " --ground-truth " +
                                path("truth.csv") + " --method mrs --protocol global --sequence-length 64 " +
                                "--queries 6 --seed 5 --output ";
  ASSERT_EQ(run(eval(arguments + path("threads_1.json") + " --threads 1")).status, 0);
  ASSERT_EQ(run(eval(arguments + path("threads_2.json") + " --threads 2")).status, 0);
  const json one = json::parse(fileContents(path("threads_1.json")));
  const json two = json::parse(fileContents(path("threads_2.json")));
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

TEST_F(EvaluatorTest, TheEvaluatorChecksWhereItWritesBeforeEvaluating) {
  std::ofstream(path("plain_file")) << "x";
  const std::string evaluation = "--reference " + path("reference") + " --query " + path("query") +
                                 " --method seqslam --protocol per-frame --sequence-length 10";
  const CommandResult plots = run(eval(evaluation + " --plots " + path("plain_file/plots")));
  EXPECT_EQ(plots.status, 1);
  EXPECT_NE(plots.err.find("mrs_vpr_eval: error: --plots '" + path("plain_file/plots") + "': cannot create the folder"),
            std::string::npos)
      << plots.err;
  EXPECT_EQ(plots.err.find("matching"), std::string::npos) << "the evaluation ran first: " << plots.err;
  const CommandResult output = run(eval(evaluation + " --output " + path("nowhere/evaluation.json")));
  EXPECT_EQ(output.status, 1);
  EXPECT_NE(
      output.err.find("--output '" + path("nowhere/evaluation.json") + "': there is no folder " + path("nowhere")),
      std::string::npos)
      << output.err;
  EXPECT_EQ(output.err.find("matching"), std::string::npos) << output.err;
  // Only the plots' own folder is created: a typo in its parent is an error, not a tree of folders.
  const CommandResult deep = run(eval(evaluation + " --plots " + path("nowhere/deep/plots")));
  EXPECT_EQ(deep.status, 1);
  EXPECT_NE(deep.err.find("--plots '" + path("nowhere/deep/plots") + "': there is no folder " + path("nowhere/deep")),
            std::string::npos)
      << deep.err;
  EXPECT_FALSE(fs::exists(path("nowhere")));
  // A run that fails after its options were checked leaves no empty --plots folder behind.
  std::ofstream(path("far_truth.csv")) << "query_index,matching_ref_indices\n0,100000\n";
  const CommandResult failed =
      run(eval(evaluation + " --ground-truth " + path("far_truth.csv") + " --plots " + path("failed_plots")));
  EXPECT_EQ(failed.status, 1);
  EXPECT_NE(failed.err.find("100000"), std::string::npos) << failed.err;
  EXPECT_FALSE(fs::exists(path("failed_plots")));
}

TEST_F(EvaluatorTest, APathThatIsNotUtf8IsWrittenAndAnExistingOutputIsKeptUntilTheNewOneIsComplete) {
  // A folder named in Latin-1, as older cameras and file systems name them: byte 0xE9 is no UTF-8.
  const std::string latin = path("caf\xe9");
  fs::copy(path("query"), latin);
  const std::string output = path("latin.json");
  std::ofstream(output) << "{\"earlier\": true}\n";
  const CommandResult result = run(eval("--reference " + path("reference") + " --query '" + latin +
                                        "' --method seqslam --protocol per-frame --sequence-length 10 --output " +
                                        output));
  ASSERT_EQ(result.status, 0) << result.err;
  const json document = json::parse(fileContents(output));
  EXPECT_EQ(document.at("summary").at("queries").get<int>(), 91);
  EXPECT_FALSE(fs::exists(output + ".part"));
}

TEST_F(EvaluatorTest, APipeGivenAsOutputIsWrittenIntoNotReplaced) {
  // As `--output /dev/stdout` into a pipe, or a named pipe another program reads: renaming a file
  // onto it replaced it, and the reader got nothing.
  const std::string fifo = path("results.fifo");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // Read as the tool writes (more than a pipe holds), without blocking: a tool that never opens the
  // pipe must fail the test, not hang it.
  const int fd = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
  ASSERT_GE(fd, 0);
  std::atomic<bool> finished{false};
  std::string received;
  std::thread reader([&] {
    char buffer[65536];
    for (;;) {
      const ssize_t count = ::read(fd, buffer, sizeof(buffer));
      if (count > 0) {
        received.append(buffer, static_cast<std::size_t>(count));
      } else if (count == 0 && finished) {
        break;  // No writer any more, and none to come.
      } else {
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      }
    }
  });
  const CommandResult result = run(eval("--reference " + path("reference") + " --query " + path("query") +
                                        " --method seqslam --protocol per-frame --sequence-length 10 --output " +
                                        fifo));
  finished = true;
  reader.join();
  ::close(fd);
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_TRUE(fs::is_fifo(fifo));
  EXPECT_FALSE(fs::exists(fifo + ".part"));
  ASSERT_FALSE(received.empty());
  EXPECT_EQ(json::parse(received).at("summary").at("queries").get<int>(), 91);
}

}  // namespace
