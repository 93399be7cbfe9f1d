// mrs_vpr_eval --plots and mrs_vpr_plot on a generated route: the PNGs are written, are valid images
// and have the size asked for; the difference pictures the plots draw on are described in the JSON.

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "mrs_vpr/synthetic_route.hpp"
#include "route_tools_fixture.hpp"

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

/// Width and height from a PNG's signature and IHDR chunk; {-1, -1} when the file is not a PNG.
std::pair<int, int> pngSize(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::array<unsigned char, 24> head{};
  in.read(reinterpret_cast<char*>(head.data()), head.size());
  const std::array<unsigned char, 8> signature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (!in || !std::equal(signature.begin(), signature.end(), head.begin()) ||
      std::string(head.begin() + 12, head.begin() + 16) != "IHDR") {
    return {-1, -1};
  }
  const auto big_endian = [&](int at) {
    return static_cast<int>((std::uint32_t{head[at]} << 24) | (std::uint32_t{head[at + 1]} << 16) |
                            (std::uint32_t{head[at + 2]} << 8) | std::uint32_t{head[at + 3]});
  };
  return {big_endian(16), big_endian(20)};
}

/// Expects a PNG of width x height that OpenCV decodes to the same size.
void expectPng(const fs::path& file, int width, int height) {
  ASSERT_TRUE(fs::exists(file)) << file;
  EXPECT_EQ(pngSize(file), std::make_pair(width, height)) << file;
  const cv::Mat image = cv::imread(file.string(), cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(image.empty()) << file << " does not decode";
  EXPECT_EQ(image.cols, width) << file;
  EXPECT_EQ(image.rows, height) << file;
}

class PlotsTest : public mrs_vpr::testing_support::RouteToolsTest {
 protected:
  /// Runs `command`; returns its exit status, and its stdout and stderr where asked.
  static int exitStatus(const std::string& command, std::string* out = nullptr, std::string* err = nullptr) {
    const mrs_vpr::testing_support::CommandResult result = run(command);
    if (out != nullptr) *out = result.out;
    if (err != nullptr) *err = result.err;
    return result.status;
  }

  static std::string evaluate(const std::string& method, const fs::path& plots) {
    return std::string(MRS_VPR_EVAL_PATH) + " --reference " + (root() / "reference").string() + " --query " +
           (root() / "query").string() + " --ground-truth " + (root() / "truth.csv").string() + " --method " + method +
           // Every frame a keyframe, so that the pictures' sizes are the traversals' own.
           " --protocol per-frame --sequence-length 10 --alignment causal --tolerance 2 --min-appearance-change 0 "
           "--plots " +
           plots.string();
  }

  /// The plotting tool, installed beside the evaluator.
  static std::string plotTool() { return (fs::path(MRS_VPR_EVAL_PATH).parent_path() / "mrs_vpr_plot").string(); }

};

TEST_F(PlotsTest, EvalWritesEveryPlotAndTheDifferencePictures) {
  const fs::path plots = root() / "plots";
  std::string out;
  std::string err;
  ASSERT_EQ(exitStatus(evaluate("seqslam", plots), &out, &err), 0) << err;
  // stdout stays the summary alone: the plotting tool's messages go to stderr.
  EXPECT_EQ(json::parse(out).at("summary").at("queries").get<int>(), 91);
  for (const char* name : {"pr_curve.png", "difference_matrix.png", "difference_band.png", "error_along_route.png"}) {
    expectPng(plots / name, 640, 480);
  }
  const json document = json::parse(std::ifstream(plots / "evaluation.json"));
  const json& pictures = document.at("difference_pictures");
  EXPECT_EQ(pictures.at("contrast_window").get<int>(), 10);
  // The whole matrix fits: one row per query frame, one column per reference frame.
  const json& overview = pictures.at("overview");
  EXPECT_EQ(overview.at("query_stride").get<int>(), 1);
  EXPECT_EQ(overview.at("reference_stride").get<int>(), 1);
  expectPng(plots / overview.at("file").get<std::string>(), 150, 100);
  // The band: one row per evaluated query frame, 50 reference frames each side of the truth.
  const json& band = pictures.at("band");
  EXPECT_EQ(band.at("half_width").get<int>(), 50);
  ASSERT_EQ(band.at("query_frames").size(), 91U);
  EXPECT_EQ(band.at("query_frames").at(0).get<int>(), 9);
  EXPECT_LT(band.at("value_min").get<double>(), band.at("value_max").get<double>());
  expectPng(plots / band.at("file").get<std::string>(), 101, 91);
}

TEST_F(PlotsTest, AnOutputBesidePlotsNamesTheirPicturesWhereTheyAreAndAnotherRunsPictureIsRefused) {
  // --output elsewhere than --plots: its pictures are named by their whole path, and draw.
  const fs::path plots = root() / "with_output";
  const fs::path output = root() / "run.json";
  std::string err;
  ASSERT_EQ(exitStatus(evaluate("seqslam", plots) + " --output " + output.string(), nullptr, &err), 0) << err;
  const json document = json::parse(std::ifstream(output));
  EXPECT_EQ(document.at("difference_pictures").at("band").at("file").get<std::string>(),
            (plots / "difference_band_values.png").string());
  ASSERT_EQ(exitStatus(plotTool() + " band " + output.string() + " -o " + (root() / "band.png").string(), nullptr,
                       &err),
            0)
      << err;
  // A picture of another run where this evaluation's should be: refused, not drawn under its truth.
  fs::copy_file(plots / "difference_band_values.png", root() / "kept_band.png");
  cv::imwrite((plots / "difference_band_values.png").string(), cv::Mat(5, 7, CV_8UC1, cv::Scalar(9)));
  EXPECT_EQ(exitStatus(plotTool() + " band " + output.string() + " -o " + (root() / "other.png").string(), nullptr,
                       &err),
            1);
  EXPECT_NE(err.find("is a picture of 5 x 7 cells, not the 91 x 101 that"), std::string::npos) << err;
  fs::remove(plots / "difference_band_values.png");
  EXPECT_EQ(exitStatus(plotTool() + " band " + output.string() + " -o " + (root() / "other.png").string(), nullptr,
                       &err),
            1);
  EXPECT_NE(err.find("which does not exist"), std::string::npos) << err;
  EXPECT_FALSE(fs::exists(root() / "other.png"));
}

TEST_F(PlotsTest, OutOfMapQueriesHaveNoBandAndNoErrorToDraw) {
  const fs::path plots = root() / "out_of_map";
  std::string err;
  ASSERT_EQ(
      exitStatus(std::string(MRS_VPR_EVAL_PATH) + " --reference " + (root() / "reference").string() + " --query " +
                     (root() / "query").string() +
                     " --out-of-map --method mrs --protocol per-frame --sequence-length 10 --plots " + plots.string(),
                 nullptr, &err),
      0)
      << err;
  expectPng(plots / "pr_curve.png", 640, 480);
  expectPng(plots / "difference_matrix.png", 640, 480);
  EXPECT_FALSE(fs::exists(plots / "difference_band.png"));
  EXPECT_FALSE(fs::exists(plots / "error_along_route.png"));
  const json document = json::parse(std::ifstream(plots / "evaluation.json"));
  EXPECT_FALSE(document.at("difference_pictures").contains("band"));
}

TEST_F(PlotsTest, AFolderUsedAgainKeepsNoPlotOfTheEarlierRun) {
  // --output inside the --plots folder, which --plots makes: allowed; --output on the JSON it writes: not.
  const fs::path plots = root() / "used_again";
  std::string err;
  ASSERT_EQ(exitStatus(evaluate("seqslam", plots) + " --output " + (plots / "run.json").string(), nullptr, &err), 0)
      << err;
  EXPECT_TRUE(fs::exists(plots / "run.json"));
  for (const char* name : {"difference_band.png", "error_along_route.png", "difference_band_values.png"}) {
    ASSERT_TRUE(fs::exists(plots / name)) << name;
  }
  EXPECT_EQ(exitStatus(evaluate("seqslam", plots) + " --output " + (plots / "evaluation.json").string(), nullptr, &err),
            1);
  EXPECT_NE(err.find("is the JSON that --plots writes there"), std::string::npos) << err;
  // A link to the file there.
  fs::create_symlink(plots / "evaluation.json", root() / "link_to_plots_json.json");
  EXPECT_EQ(exitStatus(evaluate("seqslam", plots) + " --output " + (root() / "link_to_plots_json.json").string(),
                       nullptr, &err),
            1);
  EXPECT_NE(err.find("is the JSON that --plots writes there"), std::string::npos) << err;
  // The same file named through a link to the folder.
  fs::create_directory_symlink(plots, root() / "link_to_used_again");
  EXPECT_EQ(exitStatus(evaluate("seqslam", root() / "link_to_used_again") + " --output " +
                           (plots / "evaluation.json").string(),
                       nullptr, &err),
            1);
  EXPECT_NE(err.find("is the JSON that --plots writes there"), std::string::npos) << err;
  // Queries outside the map have no band and no error to draw: the earlier run's must not pass for theirs.
  ASSERT_EQ(exitStatus(std::string(MRS_VPR_EVAL_PATH) + " --reference " + (root() / "reference").string() +
                           " --query " + (root() / "query").string() +
                           " --out-of-map --method mrs --protocol per-frame --sequence-length 10 --plots " +
                           plots.string(),
                       nullptr, &err),
            0)
      << err;
  expectPng(plots / "pr_curve.png", 640, 480);
  for (const char* name : {"difference_band.png", "error_along_route.png", "difference_band_values.png"}) {
    EXPECT_FALSE(fs::exists(plots / name)) << name;
  }
  EXPECT_TRUE(fs::exists(plots / "run.json"));  // Not a plot: the user's, left alone.
}

TEST_F(PlotsTest, PlotToolDrawsTwoMethodsInOneFigureAtTheAskedSize) {
  const fs::path mrs = root() / "mrs";
  const fs::path seqslam = root() / "seqslam";
  ASSERT_EQ(exitStatus(evaluate("mrs", mrs)), 0);
  ASSERT_EQ(exitStatus(evaluate("seqslam", seqslam)), 0);
  const fs::path both = root() / "pr_both.png";
  std::string err;
  ASSERT_EQ(exitStatus(plotTool() + " pr " + (mrs / "evaluation.json").string() + " " +
                    (seqslam / "evaluation.json").string() + " -o " + both.string() + " --dpi 50",
                nullptr, &err),
            0)
      << err;
  expectPng(both, 320, 240);
  // What it draws: the curves in colour, and the second method's beside the first one's.
  const fs::path one = root() / "pr_one.png";
  ASSERT_EQ(exitStatus(plotTool() + " pr " + (mrs / "evaluation.json").string() + " -o " + one.string() + " --dpi 50"),
            0);
  const cv::Mat drawn_both = cv::imread(both.string(), cv::IMREAD_COLOR);
  const cv::Mat drawn_one = cv::imread(one.string(), cv::IMREAD_COLOR);
  ASSERT_EQ(drawn_both.size(), drawn_one.size());
  EXPECT_GT(cv::norm(drawn_both, drawn_one, cv::NORM_L1), 0.0);
  cv::Mat hsv;
  cv::cvtColor(drawn_both, hsv, cv::COLOR_BGR2HSV);
  std::vector<cv::Mat> channels;
  cv::split(hsv, channels);
  EXPECT_GT(cv::countNonZero(channels[1] > 100), 50) << "no coloured curve in " << both;
  // Alone, with another size.
  const fs::path error = root() / "error_small.png";
  ASSERT_EQ(exitStatus(plotTool() + " error " + (mrs / "evaluation.json").string() + " -o " + error.string() +
                " --size 5 3 --dpi 80"),
            0);
  expectPng(error, 400, 240);
}

TEST_F(PlotsTest, PlotToolDrawsTheBenchmarkCurves) {
  // The document mrs_vpr_real_benchmark --json writes, with its fields, for two maps and two lengths.
  json rows = json::array();
  for (const char* method : {"seqslam", "mrs"}) {
    for (int frames : {1783, 9137}) {
      for (int length : {100, 300}) {
        const double time = (std::string(method) == "mrs" ? 0.05 : 1.0) * frames * length / 10000.0;
        rows.push_back({{"setting", "global N=" + std::to_string(length) + " M=" + std::to_string(frames)},
                        {"method", method},
                        {"protocol", "global"},
                        {"out_of_map", false},
                        {"reference_frames", frames},
                        {"sequence_length", length},
                        {"summary", {{"queries", 100}, {"top1", 1.0}, {"median_time_ms", time}}}});
      }
    }
  }
  const json bench = {{"part", "check"}, {"threads", 1}, {"tolerance", 5}, {"queries", 100}, {"seed", 42},
                      {"rows", rows}};
  const fs::path folder = root() / "bench";
  fs::create_directories(folder);
  std::ofstream(folder / "bench.json") << bench.dump();
  std::string err;
  ASSERT_EQ(exitStatus(plotTool() + " benchmark " + (folder / "bench.json").string(), nullptr, &err), 0) << err;
  expectPng(folder / "success_vs_n.png", 640, 480);
  expectPng(folder / "time_vs_m.png", 640, 480);
}

TEST_F(PlotsTest, PlotToolReportsBadInputInOneLine) {
  const fs::path bad = root() / "not_an_evaluation.json";
  std::ofstream(bad) << R"({"method": "mrs"})";
  std::string err;
  EXPECT_EQ(exitStatus(plotTool() + " error " + bad.string() + " -o " + (root() / "x.png").string(), nullptr, &err), 1);
  EXPECT_EQ(err.rfind("mrs_vpr_plot: error: missing field", 0), 0U) << err;
  EXPECT_FALSE(fs::exists(root() / "x.png"));
}

TEST_F(PlotsTest, PlotToolReportsJsonOfAnotherShapeInOneLine) {
  // Each of these ended in a Python traceback.
  struct Case {
    std::string document;
    std::string command;
    std::string problem;
  };
  const std::string other_shape = "not the JSON that mrs_vpr_eval or mrs_vpr_real_benchmark writes";
  const std::vector<Case> cases = {
      {"[1, 2, 3]", "pr", "holds a JSON list, not the object that mrs_vpr_eval --output"},
      {R"("text")", "matrix", "holds a JSON str, not the object"},
      {R"({"records": 5, "summary": {"tolerance": 2}})", "error", other_shape},
      {R"({"records": [1, 2], "summary": {"tolerance": 2}})", "error", other_shape},
      {"[]", "benchmark", "holds a JSON list"},
      // What --output writes: records and a summary, but no difference pictures.
      {R"({"records": [], "summary": {"tolerance": 2}})", "matrix", "writes them with --plots DIR"},
      {R"({"records": [], "summary": {"tolerance": 2}})", "band", "writes them with --plots DIR"},
  };
  int index = 0;
  for (const Case& bad : cases) {
    SCOPED_TRACE(bad.command + " " + bad.document);
    const fs::path file = root() / ("shape" + std::to_string(index++) + ".json");
    std::ofstream(file) << bad.document;
    std::string err;
    EXPECT_EQ(exitStatus(plotTool() + " " + bad.command + " " + file.string() +
                      (bad.command == "benchmark" ? "" : " -o " + (root() / "x.png").string()),
                  nullptr, &err),
              1);
    EXPECT_EQ(err.rfind("mrs_vpr_plot: error: " + file.string(), 0), 0U) << err;
    EXPECT_NE(err.find(bad.problem), std::string::npos) << err;
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  }
  EXPECT_FALSE(fs::exists(root() / "x.png"));
}

TEST_F(PlotsTest, PlotToolWritesAndReportsTheFileItIsGiven) {
  const fs::path evaluation = root() / "named" / "evaluation.json";
  ASSERT_EQ(exitStatus(evaluate("seqslam", evaluation.parent_path())), 0);
  // Without an extension: NAME.png, as matplotlib writes it, and reported so.
  std::string out;
  ASSERT_EQ(exitStatus(plotTool() + " pr " + evaluation.string() + " -o " + (root() / "curve").string(), &out), 0);
  EXPECT_EQ(out, "wrote " + (root() / "curve.png").string() + "\n");
  expectPng(root() / "curve.png", 640, 480);
  EXPECT_FALSE(fs::exists(root() / "curve"));
  // A folder: refused, rather than FOLDER.png written beside it.
  fs::create_directories(root() / "pictures");
  std::string err;
  EXPECT_EQ(
      exitStatus(plotTool() + " error " + evaluation.string() + " -o " + (root() / "pictures").string(), &out, &err),
      1);
  EXPECT_EQ(err, "mrs_vpr_plot: error: -o " + (root() / "pictures").string() +
                     " is a folder: give the file to write, such as " + (root() / "pictures" / "plot.png").string() +
                     "\n");
  EXPECT_FALSE(fs::exists(root() / "pictures.png"));
  EXPECT_TRUE(fs::is_empty(root() / "pictures"));
}

}  // namespace
