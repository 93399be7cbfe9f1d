// The benchmarks run as a user runs them, on a generated route standing in for the real data: their
// usage, one-line errors with exit code 1 on bad options, and the rows each option asks for.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <iterator>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "mrs_vpr/parameters.hpp"
#include "route_tools_fixture.hpp"

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using mrs_vpr::testing_support::CommandResult;
using mrs_vpr::testing_support::fileContents;

class BenchmarksTest : public mrs_vpr::testing_support::RouteToolsTest {};

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
void expectBenchmarkError(const Benchmark& benchmark, const CommandResult& result, const std::string& text) {
  EXPECT_EQ(result.status, 1) << benchmark.name << "\n" << result.err;
  EXPECT_EQ(result.err.rfind(benchmark.name + ": error: ", 0), 0U) << result.err;
  EXPECT_NE(result.err.find(text), std::string::npos) << benchmark.name << "\n" << result.err;
  EXPECT_EQ(std::count(result.err.begin(), result.err.end(), '\n'), 1) << result.err;
  EXPECT_EQ(result.out, "") << benchmark.name;
}

TEST_F(BenchmarksTest, BenchmarksPrintTheirUsageOnHelp) {
  for (const Benchmark& benchmark : benchmarks()) {
    for (const char* help : {" --help", " -h"}) {
      const CommandResult result = run(benchmark.path + help);
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
  EXPECT_NE(run(std::string(MRS_VPR_REAL_BENCHMARK_PATH) + " --help").out.find("--per-frame-lengths arg (=10,50)"),
            std::string::npos);
  EXPECT_NE(run(std::string(MRS_VPR_MAP_SCALE_BENCHMARK_PATH) + " --help").out.find("--sizes arg (=10k,100k,1M)"),
            std::string::npos);
}

TEST_F(BenchmarksTest, BenchmarksRefuseBadOptionsInOneLineNamingThem) {
  for (const Benchmark& benchmark : benchmarks()) {
    const std::string command = benchmark.path + " " + benchmark.required;
    expectBenchmarkError(benchmark, run(command + " --no-such-option 3"), "unrecognised option '--no-such-option'");
    expectBenchmarkError(benchmark, run(command + " --queries"), "option '--queries' is missing");
    expectBenchmarkError(benchmark, run(command + " --queries many"),
                         "the argument ('many') for option '--queries' is invalid");
    // A list with a bad, empty or trailing item is refused whole.
    for (const std::string list : {"10,x", "10,,20", "10,"}) {
      const CommandResult result = run(command + " " + benchmark.list_option + " " + list);
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
  expectBenchmarkError(real, run(real.path + " --data nowhere --per-frame-lengths 20,1"),
                       "--per-frame-lengths takes sequence lengths >= 2");
  const Benchmark scale = benchmarks()[2];
  expectBenchmarkError(scale, run(scale.path + " --data nowhere --sizes 10k,lots"), "bad size 'lots'");
  expectBenchmarkError(scale, run(scale.path + " --data nowhere --sizes 1k"), "bad size '1k'");
  // Before any table header: a folder without the shared data is no data.
  expectBenchmarkError(scale, run(scale.path + " --data nowhere"), "--data nowhere has no folder nordland/summer");
  const Benchmark debug = benchmarks()[3];
  expectBenchmarkError(debug, run(debug.path + " --reference nowhere"), "the option '--query' is required but missing");
  expectBenchmarkError(debug, run(debug.path + " --reference a --query b --picture-method best"),
                       "--picture-method must be mrs or seqslam");
  const Benchmark search = benchmarks()[0];
  expectBenchmarkError(search, run(search.path + " --threads 1,0"), "--threads takes counts >= 1");
  expectBenchmarkError(search, run(search.path + " --reference-frames 600 --sequence-length 600"),
                       "--sequence-length must be in 2..490");
}

TEST_F(BenchmarksTest, TheGeneratedRouteBenchmarkRunsWithTheGivenOptions) {
  const CommandResult result = run(std::string(MRS_VPR_BENCHMARK_PATH) +
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
  const CommandResult judged = run(std::string(MRS_VPR_BENCHMARK_PATH) +
                                   " --reference-frames 600 --sequence-length 60 --queries 5 --threads 1 --min-time 0");
  ASSERT_EQ(judged.status, 0) << judged.err;
  EXPECT_NE(judged.out.find("\n1        seqslam     1.000 "), std::string::npos) << judged.out;
  EXPECT_NE(judged.out.find("\n1        mrs         1.000 "), std::string::npos) << judged.out;
}

TEST_F(BenchmarksTest, TheDebugImageBenchmarkRunsWithTheGivenOptions) {
  const std::string picture = path("debug_image.png");
  const CommandResult result =
      run(std::string(MRS_VPR_DEBUG_IMAGE_BENCHMARK_PATH) + " --reference " + path("reference") + " --query " +
          path("query") + " --lengths 10,20 --queries 2 --runs 1 --methods seqslam --threads 1 --output " + picture +
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

TEST_F(BenchmarksTest, TheRealDataBenchmarkRunsWithTheGivenOptions) {
  const fs::path data = realDataLayout(root());
  const std::string output = path("real_benchmark.json");
  const CommandResult result =
      run(std::string(MRS_VPR_REAL_BENCHMARK_PATH) + " --data " + data.string() +
          " --part all --references 1.8k --lengths 20,30 --queries 3 --methods seqslam --skip-per-frame --skip-drives"
          " --tolerance 4 --seed 5 --json " +
          output);
  ASSERT_EQ(result.status, 0) << result.err;
  const json document = json::parse(fileContents(output));
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

TEST_F(BenchmarksTest, TheRealDataBenchmarkReplaysCameraDrivesThroughContinuousModeAndTheEvaluator) {
  const fs::path data = realDataLayout(root());
  const std::string output = path("real_benchmark_drives.json");
  const CommandResult result = run(cameraDrivesCommand(data, "", output));
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_NE(result.out.find("Camera drives (make_drive --seed 5 and 6)"), std::string::npos) << result.out;
  const json rows = json::parse(fileContents(output)).at("rows");
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
    // None is asked about here: questions begin once the map holds 2 x 20 + recent_exclusion keyframes,
    // more than both drives keep together (the next test asks).
    EXPECT_GT(row.at("keyframes").get<int>(), 0);
    EXPECT_EQ(row.at("queries").get<int>(), 0);
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
  EXPECT_LE(rows[1].at("largest_wrong_error_places").get<int>(),
            rows[1].at("largest_wrong_error_route_frames").get<int>());
  EXPECT_EQ(rows[1].at("setting"), "camera drive continuous revisit");
  EXPECT_EQ(rows[2].at("setting"), "camera drives per-frame (mrs_vpr_eval)");
  EXPECT_EQ(rows[2].at("protocol"), "per-frame");
  EXPECT_GT(rows[2].at("summary").at("queries").get<int>(), 0);
}

TEST_F(BenchmarksTest, TheRealDataBenchmarksDrivesKeyframeAtTheThresholdGiven) {
  const fs::path data = realDataLayout(root());
  const std::string output = path("real_benchmark_every_frame.json");
  const CommandResult result = run(cameraDrivesCommand(data, " --drive-min-appearance-change 0", output));
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_NE(result.out.find("keyframes by appearance change 0.00"), std::string::npos) << result.out;
  const json rows = json::parse(fileContents(output)).at("rows");
  ASSERT_EQ(rows.size(), 3U) << rows.dump();
  // At 0 every frame is a keyframe, stopped ones included (at the default, stops add almost none).
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(rows[i].at("stopped_keyframes"), rows[i].at("drive").at("stopped_frames")) << rows[i].dump();
    // With as many keyframes, continuous mode asks on both drives.
    EXPECT_GT(rows[i].at("queries").get<int>(), 0) << rows[i].dump();
  }
  // Each keyframe once at most (the revisit's first questions may be about the map drive's last ones).
  EXPECT_LE(rows[0].at("queries").get<int>() + rows[1].at("queries").get<int>(),
            rows[0].at("keyframes").get<int>() + rows[1].at("keyframes").get<int>());
}

TEST_F(BenchmarksTest, TheRealDataBenchmarksDrivesAcceptAtTheThresholdGiven) {
  const fs::path data = realDataLayout(root());
  const std::string output = path("real_benchmark_threshold.json");
  // No confidence reaches 1000: nothing is accepted, on either drive.
  const CommandResult result = run(cameraDrivesCommand(data, " --drive-accept-threshold 1000", output));
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_NE(result.out.find("accepted at confidence 1000.0"), std::string::npos) << result.out;
  const json rows = json::parse(fileContents(output)).at("rows");
  ASSERT_EQ(rows.size(), 3U) << rows.dump();
  for (std::size_t i = 0; i < 2; ++i) EXPECT_EQ(rows[i].at("accepted"), 0) << rows[i].dump();
  EXPECT_EQ(rows[2].at("summary").at("accepted"), 0) << rows[2].dump();
  const CommandResult refused = run(cameraDrivesCommand(data, " --drive-accept-threshold -1", output));
  EXPECT_NE(refused.status, 0);
  EXPECT_EQ(refused.out.find("Camera drives"), std::string::npos) << "refused before any drive: " << refused.out;
  EXPECT_NE(refused.err.find("sequence/accept_threshold must be in 0..1000, got -1"), std::string::npos) << refused.err;
}

TEST_F(BenchmarksTest, TheRealDataBenchmarkListsTheStretchesNoClosureConfirmed) {
  const fs::path data = realDataLayout(root());
  const std::string output = path("real_benchmark_missed.json");
  // Nothing is accepted at 1000: every stretch of the revisit is missed, and listed with its answers
  // (every frame a keyframe, so that this short route is asked about).
  const CommandResult result =
      run("MRS_VPR_SHOW_MISSED=1 " +
          cameraDrivesCommand(data, " --drive-accept-threshold 1000 --drive-min-appearance-change 0", output));
  ASSERT_EQ(result.status, 0) << result.err;
  const json revisit = json::parse(fileContents(output)).at("rows").at(1);
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

TEST_F(BenchmarksTest, TheRealDataBenchmarkRefusesBadDriveSettingsBeforeReadingFrames) {
  // "nowhere" holds no frames: each refusal names the setting, not the missing data.
  const std::string command = std::string(MRS_VPR_REAL_BENCHMARK_PATH) + " --data " + path("nowhere");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {" --drive-queries all", "--drive-queries must be newest or each, got 'all'"},
      {" --drive-seeds 0", "--drive-seeds must be >= 1, got 0"},
      {" --drive-alignment ahead", "sequence/alignment must be one of causal, centred, got 'ahead'"},
      {" --drive-length 1", "sequence/sequence_length"},
      {" --drive-alignment-slack -1", "sequence/alignment_slack"}};
  for (const auto& [options, message] : cases) {
    const CommandResult refused = run(command + options);
    EXPECT_NE(refused.status, 0) << options;
    EXPECT_NE(refused.err.find(message), std::string::npos) << options << ": " << refused.err;
    EXPECT_EQ(refused.err.find("nowhere"), std::string::npos) << options << ": " << refused.err;
  }
}

TEST_F(BenchmarksTest, TheRealDataBenchmarksDrivesLeaveOutTheFirstPassAlone) {
  // mrs-first-pass is a search of the global and per-frame rows, not a method of the node: the drives
  // run the other methods and say so, instead of failing after every other row.
  const fs::path data = realDataLayout(root());
  const std::string output = path("real_benchmark_first_pass.json");
  const CommandResult result = run(std::string(MRS_VPR_REAL_BENCHMARK_PATH) + " --data " + data.string() +
                                   " --part all --references 1.8k --methods seqslam,mrs-first-pass --skip-per-frame"
                                   " --skip-global --seed 5 --json " +
                                   output);
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_NE(result.err.find("mrs-first-pass is not a method of the node"), std::string::npos) << result.err;
  const json rows = json::parse(fileContents(output)).at("rows");
  ASSERT_EQ(rows.size(), 3U) << rows.dump();
  for (const json& row : rows) EXPECT_EQ(row.at("method"), "seqslam") << row.dump();
}

TEST_F(BenchmarksTest, TheRealDataBenchmarksPerFrameRowsTakeTheGivenLengths) {
  const fs::path data = realDataLayout(root());
  const std::string output = path("real_benchmark_per_frame.json");
  const CommandResult result = run(std::string(MRS_VPR_REAL_BENCHMARK_PATH) + " --data " + data.string() +
                                   " --part all --references 1.8k --methods seqslam --skip-global --skip-drives"
                                   " --per-frame-lengths 12 --json " +
                                   output);
  ASSERT_EQ(result.status, 0) << result.err;
  const json rows = json::parse(fileContents(output)).at("rows");
  int per_frame_rows = 0;
  for (const json& row : rows) {
    if (row.at("protocol").get<std::string>() != "per-frame") continue;
    ++per_frame_rows;
    EXPECT_EQ(row.at("sequence_length"), 12) << row.dump();
  }
  // The route's map, the corridor in it, Nordland in the corridor's map, small maps of 20 to 100 frames.
  EXPECT_GE(per_frame_rows, 4) << result.out;
}

TEST_F(BenchmarksTest, TheMapScaleBenchmarkRunsWithTheGivenOptions) {
  const fs::path data = realDataLayout(root());
  const fs::path maps = path("maps");
  const CommandResult result = run(std::string(MRS_VPR_MAP_SCALE_BENCHMARK_PATH) + " --data " + data.string() +
                                   " --sizes 2k,2.5k --dir " + maps.string() +
                                   " --lengths 10 --queries 2 --brute-queries 1 --threads 1 --periods 2"
                                   " --keyframes-per-period 1 --seed 4 --load-map");
  ASSERT_EQ(result.status, 0) << result.err;
  EXPECT_NE(result.out.find("queries of N = 10, 2 per map (1 for brute force), threads 1, seed 4"), std::string::npos)
      << result.out;
  // --load-map reaches each child: a node's map loads each map, then again.
  EXPECT_NE(result.out.find("       2k  ~load_map of 2000 frames into a node's empty map: "), std::string::npos)
      << result.out;
  EXPECT_NE(result.out.find("     2500  ~load_map of 2500 frames into a node's empty map: "), std::string::npos)
      << result.out;
  EXPECT_FALSE(fs::exists(maps / "map-2k-hog-seed4.db.load_map.db")) << "the node's scratch map was left";
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
  EXPECT_NE(result.out.find("       2k map: hog (128 x 64 window, cells of 16 px, 9 bins)"), std::string::npos)
      << result.out;
  // A map kept from an earlier run is measured again only when it is of the front end asked for and of
  // the same data: another front end's parameters write it anew.
  const std::string again = std::string(MRS_VPR_MAP_SCALE_BENCHMARK_PATH) + " --data " + data.string() +
                            " --sizes 2k --dir " + maps.string() +
                            " --lengths 10 --queries 1 --brute-queries 1 --threads 1 --periods 0 --seed 4";
  const CommandResult reused = run(again);
  ASSERT_EQ(reused.status, 0) << reused.err;
  EXPECT_EQ(reused.err.find("wrote "), std::string::npos) << reused.err;
  const CommandResult blurred = run(again + " --hog-blur 1");
  ASSERT_EQ(blurred.status, 0) << blurred.err;
  EXPECT_NE(blurred.err.find("wrote "), std::string::npos) << blurred.err;
  EXPECT_NE(blurred.out.find("       2k map: hog (128 x 64 window, cells of 16 px, 9 bins, blur 1 px)"),
            std::string::npos)
      << blurred.out;
  // Continuous mode: one row a method, its queries' CPU share at a 1 s period.
  EXPECT_NE(result.out.find("mrs continuous mode: 1 keyframes a period"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("seqslam continuous mode: 1 keyframes a period"), std::string::npos) << result.out;
  // How fast the machine streams each map: the cost of a new keyframe's row, which bounds the rows' speed-up.
  for (const std::string size : {"2k", "2500"}) {
    EXPECT_NE(result.out.find(
                  size + "  map stream: one keyframe against every map frame (a new keyframe's row), median of 7: "),
              std::string::npos)
        << size << "\n"
        << result.out;
  }
}

}  // namespace
