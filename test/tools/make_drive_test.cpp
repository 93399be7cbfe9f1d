// make_drive as a user runs it: a drive of a generated route's folder, its drive.csv, the ground truth
// of two drives, and mrs_vpr_eval on the drives with that truth; one-line errors on bad input.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "mrs_vpr/evaluation/drive_file.hpp"
#include "mrs_vpr/synthetic_route.hpp"
#include "route_folders.hpp"
#include "support/command_run.hpp"
#include "support/route_fixture.hpp"
#include "support/temporary_folder.hpp"

namespace {

namespace fs = std::filesystem;
using mrs_vpr::testing_support::CommandResult;
using mrs_vpr::testing_support::fileContents;
using mrs_vpr::testing_support::runCommand;
using mrs_vpr::testing_support::TemporaryFolder;

class MakeDriveTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    folder_ = new TemporaryFolder("mrs_vpr_make_drive_test");
    // Two traversals of one route frame for frame (speed 1, from the same place): summer and winter.
    mrs_vpr::SyntheticRouteParams params;
    params.reference_frames = 400;
    params.query_frames = 400;
    params.speed_min = params.speed_max = 1.0;
    const mrs_vpr::SyntheticRoute route = mrs_vpr::generateSyntheticRoute(params);
    mrs_vpr::testing_support::writeImageFolder(path("summer"), route.reference);
    mrs_vpr::testing_support::writeImageFolder(path("winter"), route.query);
  }
  static void TearDownTestSuite() {
    delete folder_;
    folder_ = nullptr;
  }

  static std::string path(const std::string& name) { return folder_->path(name); }

  static CommandResult run(const std::string& program, const std::string& arguments) {
    return runCommand(program + " " + arguments, *folder_);
  }
  static CommandResult makeDrive(const std::string& arguments) { return run(MAKE_DRIVE_PATH, arguments); }

  /// Expects exit code 1 and one line "make_drive: error: ..." that contains `text`.
  static void expectError(const std::string& arguments, const std::string& text) {
    const CommandResult result = makeDrive(arguments);
    EXPECT_EQ(result.status, 1) << arguments << "\n" << result.err;
    EXPECT_EQ(result.err.rfind("make_drive: error: ", 0), 0U) << result.err;
    EXPECT_NE(result.err.find(text), std::string::npos) << result.err;
    EXPECT_EQ(result.err.find('\n'), result.err.size() - 1) << result.err;
  }

  static std::vector<std::string> imagesIn(const std::string& folder) {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(folder)) {
      if (entry.path().extension() == ".png") names.push_back(entry.path().filename().string());
    }
    std::sort(names.begin(), names.end());
    return names;
  }

  static TemporaryFolder* folder_;
};

TemporaryFolder* MakeDriveTest::folder_ = nullptr;

constexpr const char* kSmallDrive =
    " --stops 3 --stop-frames-min 20 --stop-frames-max 30 --slow-frames 30 --fast-frames 30";

TEST_F(MakeDriveTest, WritesTheDriveAsImagesWithTheRouteFrameOfEach) {
  const CommandResult result = makeDrive("--images " + path("summer") + " --begin 100 --end 300 --seed 4 --output " +
                                         path("part") + kSmallDrive);
  ASSERT_EQ(result.status, 0) << result.err;
  const std::vector<mrs_vpr::DriveFrame> frames = mrs_vpr::readDriveFile(path("part") + "/drive.csv");
  const std::vector<std::string> images = imagesIn(path("part"));
  ASSERT_EQ(images.size(), frames.size());
  EXPECT_EQ(images.front(), "000000.png");
  int stopped = 0;
  for (const mrs_vpr::DriveFrame& frame : frames) {
    EXPECT_GE(frame.route_frame, 100);  // Numbered as the folder's images.
    EXPECT_LT(frame.route_frame, 300);
    stopped += frame.kind == mrs_vpr::DriveFrameKind::kStopped ? 1 : 0;
  }
  EXPECT_GE(stopped, 3 * 20);
  EXPECT_LE(stopped, 3 * 30);
  EXPECT_EQ(static_cast<int>(frames.size()), 200 - 15 + 30 + stopped);
  // A moving frame is the route's image itself.
  ASSERT_EQ(frames.front().kind, mrs_vpr::DriveFrameKind::kMoving);
  EXPECT_EQ(fileContents(path("part/000000.png")), fileContents(path("summer/00100.png")));

  // The same seed, the same drive; an existing drive is replaced only with --force.
  expectError("--images " + path("summer") + " --begin 100 --end 300 --seed 4 --output " + path("part") + kSmallDrive,
              "exists and is not empty; use --force");
  ASSERT_EQ(makeDrive("--images " + path("summer") + " --begin 100 --end 300 --seed 4 --force --output " +
                      path("again") + kSmallDrive)
                .status,
            0);
  EXPECT_EQ(fileContents(path("again/drive.csv")), fileContents(path("part/drive.csv")));
  EXPECT_EQ(fileContents(path("again/") + images.back()), fileContents(path("part/") + images.back()));
  EXPECT_FALSE(fs::exists(path("part.part")));
}

TEST_F(MakeDriveTest, SixteenBitFramesAreDrawnAsTheirEightBitOriginals) {
  // 16-bit PNGs of the same pictures, as a camera's raw frames may be stored.
  fs::create_directories(path("summer16"));
  for (const std::string& name : imagesIn(path("summer"))) {
    cv::Mat wide;
    cv::imread(path("summer/" + name), cv::IMREAD_UNCHANGED).convertTo(wide, CV_16U, 257.0);
    ASSERT_TRUE(cv::imwrite(path("summer16/" + name), wide));
  }
  const CommandResult result = makeDrive("--images " + path("summer16") + " --begin 100 --end 300 --seed 4 --output " +
                                         path("part16") + kSmallDrive);
  ASSERT_EQ(result.status, 0) << result.err;
  // A moving frame is the route's image itself, in 8 bits.
  const cv::Mat first = cv::imread(path("part16/000000.png"), cv::IMREAD_UNCHANGED);
  const cv::Mat original = cv::imread(path("summer/00100.png"), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(first.type(), original.type());
  EXPECT_EQ(cv::norm(first, original, cv::NORM_INF), 0.0);
}

TEST_F(MakeDriveTest, TwoDrivesAndTheirTruthAreWhatTheEvaluatorReads) {
  ASSERT_EQ(makeDrive("--images " + path("summer") + " --seed 1 --output " + path("map") + kSmallDrive).status, 0);
  ASSERT_EQ(makeDrive("--images " + path("winter") + " --begin 0 --end 250 --seed 2 --output " + path("revisit") +
                      kSmallDrive)
                .status,
            0);
  const CommandResult truth =
      makeDrive("--ground-truth " + path("truth.csv") + " --reference " + path("map") + " --query " + path("revisit"));
  ASSERT_EQ(truth.status, 0) << truth.err;

  // Query frame i: the map's frames within 2 route frames of its own.
  const std::vector<int> map = mrs_vpr::routeFramesOf(mrs_vpr::readDriveFile(path("map/drive.csv")));
  const std::vector<int> revisit = mrs_vpr::routeFramesOf(mrs_vpr::readDriveFile(path("revisit/drive.csv")));
  std::ifstream file(path("truth.csv"));
  std::string line;
  std::getline(file, line);
  EXPECT_EQ(line, "query_index,matching_ref_indices");
  int rows = 0;
  while (std::getline(file, line)) {
    std::istringstream row(line);
    int query = -1;
    char comma = 0;
    row >> query >> comma;
    ASSERT_EQ(query, rows++);
    int reference = -1;
    int matches = 0;
    while (row >> reference) {
      EXPECT_LE(std::abs(map[static_cast<std::size_t>(reference)] - revisit[static_cast<std::size_t>(query)]), 2);
      ++matches;
    }
    EXPECT_GT(matches, 0) << line;
  }
  EXPECT_EQ(rows, static_cast<int>(revisit.size()));

  // The generated route's places stand out from one another over 20 keyframes, not over 10.
  const CommandResult evaluated =
      run(MRS_VPR_EVAL_PATH, "--reference " + path("map") + " --query " + path("revisit") + " --ground-truth " +
                                 path("truth.csv") + " --protocol per-frame --sequence-length 20");
  ASSERT_EQ(evaluated.status, 0) << evaluated.err;
  const nlohmann::json summary = nlohmann::json::parse(evaluated.out).at("summary");
  EXPECT_GT(summary.at("queries").get<int>(), 0);
  EXPECT_GT(summary.at("accepted").get<int>(), 0);
  EXPECT_EQ(summary.at("accepted_precision").get<double>(), 1.0) << evaluated.out;
}

TEST_F(MakeDriveTest, PlacesFromTheRouteMakeAStandingRecordingOnePlace) {
  // A route of 40 frames whose recording camera stood from frame 10 to 19 (noisy copies of frame 10).
  std::vector<cv::Mat> route = mrs_vpr::testing_support::shortRouteImages(40);
  cv::RNG rng(7);
  for (int i = 11; i < 20; ++i) {
    cv::Mat noise(route[10].size(), CV_16SC(route[10].channels()));
    rng.fill(noise, cv::RNG::NORMAL, 0, 1);
    cv::add(route[10], noise, route[static_cast<std::size_t>(i)], cv::noArray(), route[10].type());
  }
  mrs_vpr::testing_support::writeImageFolder(path("standing_route"), route);
  // Two drives of it, frame for frame (only their drive.csv is read).
  std::vector<mrs_vpr::DriveFrame> frames(route.size());
  for (std::size_t i = 0; i < frames.size(); ++i) frames[i].route_frame = static_cast<int>(i);
  for (const std::string name : {"standing_map", "standing_revisit"}) {
    fs::create_directories(path(name));
    mrs_vpr::writeDriveFile(path(name + "/drive.csv"), frames);
  }
  const auto truthOfFrame = [&](const std::string& extra, int query) {
    const CommandResult result = makeDrive("--ground-truth " + path("standing.csv") + " --force --reference " +
                                           path("standing_map") + " --query " + path("standing_revisit") + extra);
    EXPECT_EQ(result.status, 0) << result.err;
    std::ifstream file(path("standing.csv"));
    std::string line;
    for (int row = 0; row <= query + 1; ++row) std::getline(file, line);
    std::istringstream matches(line.substr(line.find(',') + 1));
    std::vector<int> result_frames;
    for (int frame = 0; matches >> frame;) result_frames.push_back(frame);
    return result_frames;
  };
  // By route frames, frame 18 is 2 frames from 16..20; as places, the whole stand and 2 places around it.
  EXPECT_EQ(truthOfFrame("", 18), (std::vector<int>{16, 17, 18, 19, 20}));
  EXPECT_EQ(truthOfFrame(" --places-from " + path("standing_route"), 18),
            (std::vector<int>{8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21}));
  EXPECT_EQ(truthOfFrame(" --places-from " + path("standing_route") + "," + path("standing_route"), 30),
            (std::vector<int>{28, 29, 30, 31, 32}));

  const CommandResult mismatched = makeDrive("--ground-truth " + path("standing.csv") + " --force --reference " +
                                             path("standing_map") + " --query " + path("standing_revisit") +
                                             " --places-from " + path("standing_route") + "," + path("summer"));
  EXPECT_EQ(mismatched.status, 1);
  EXPECT_NE(mismatched.err.find("must show the same route frames"), std::string::npos) << mismatched.err;
}

TEST_F(MakeDriveTest, BadInputGivesOneLineAndExitCodeOne) {
  expectError("--images " + path("summer"), "a drive needs --images and --output");
  expectError("--images " + path("summer") + " --output " + path("x") + " --query " + path("x"),
              "give either --images and --output (a drive) or --ground-truth");
  expectError("--images " + path("summer") + " --output " + path("x") + " --begin 300 --end 200",
              "--begin 300 and --end 200 must satisfy 0 <= begin < end <= 400");
  expectError("--images " + path("summer") + " --output " + path("x") + " --seed -1", "--seed must be >= 0, got -1");
  expectError("--images " + path("summer") + " --output " + path("x") + " --end 150",
              "a route of 150 frames cannot hold a half-speed stretch of 100");
  expectError("--images " + path("summer") + " --output " + path("x") + " --stop-frames-min 40 --stop-frames-max 10",
              "stop_frames_max must be >= stop_frames_min (40), got 10");
  expectError("--images " + path("nowhere") + " --output " + path("x"), "does not exist");
  // --force replaces a drive, never another folder.
  expectError("--images " + path("summer") + " --output " + path("winter") + " --force", "holds no drive.csv");
  EXPECT_EQ(imagesIn(path("winter")).size(), 400U);
  expectError("--ground-truth " + path("t.csv") + " --reference " + path("summer") + " --query " + path("summer"),
              "cannot open drive file '" + path("summer") + "/drive.csv'");
  expectError("--ground-truth " + path("t.csv") + " --reference " + path("summer"),
              "the ground truth needs --ground-truth, --reference and --query");
  expectError("--ground-truth " + path("t.csv") + " --reference " + path("summer") + " --query " + path("winter") +
                  " --places-from ''",
              "--places-from was given an empty path");
  EXPECT_FALSE(fs::exists(path("x")));
  // Only the drive's own folder is created: a typo in its parent is an error, not a tree of folders.
  expectError("--images " + path("summer") + " --output " + path("nowhere/deep/x"),
              "--output '" + path("nowhere/deep/x") + "': there is no folder " + path("nowhere/deep"));
  EXPECT_FALSE(fs::exists(path("nowhere")));
  // A ground truth written into a drive it reads would be read as the drive's file next time.
  expectError("--ground-truth " + path("summer/t.csv") + " --reference " + path("summer") + " --query " +
                  path("winter"),
              "--ground-truth '" + path("summer/t.csv") + "' lies inside the folder '" + path("summer") + "'");
  // An image of another size met half-way: the one-line error, and nothing half-written left behind.
  fs::copy(path("summer"), path("mixed"));
  cv::imwrite(path("mixed/00300.png"), cv::Mat(16, 16, CV_8UC3, cv::Scalar::all(90)));
  expectError("--images " + path("mixed") + " --output " + path("x"), "all images of a route must have one size");
  EXPECT_FALSE(fs::exists(path("x")));
  EXPECT_FALSE(fs::exists(path("x.part")));
}

}  // namespace
