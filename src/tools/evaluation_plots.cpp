#include "evaluation_plots.hpp"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <system_error>

#include "mrs_vpr/evaluation/difference_picture.hpp"
#include "mrs_vpr/image_codecs.hpp"

extern char** environ;  // NOLINT: POSIX passes the environment on to the plotting tool.

namespace mrs_vpr {
namespace tools {
namespace {

using json = nlohmann::ordered_json;
namespace fs = std::filesystem;

// Bounds that keep the pictures small (tens to hundreds of KB) and cheap to compute: the overview
// costs kOverviewRows x M descriptor differences, so it is left out for very large maps.
constexpr int kOverviewRows = 400;
constexpr int kOverviewColumns = 400;
constexpr int kOverviewMaxReference = 20000;
constexpr int kBandRows = 400;
constexpr int kBandHalfWidth = 50;

/// Writes `values` as an 8-bit PNG: 0 for NaN, 1..255 spread linearly over the finite values' range.
json writeQuantised(const cv::Mat& values, const fs::path& file) {
  float low = std::numeric_limits<float>::infinity();
  float high = -std::numeric_limits<float>::infinity();
  for (int r = 0; r < values.rows; ++r) {
    for (int c = 0; c < values.cols; ++c) {
      const float value = values.at<float>(r, c);
      if (!std::isfinite(value)) continue;
      low = std::min(low, value);
      high = std::max(high, value);
    }
  }
  if (!(low <= high)) low = high = 0.0F;  // Nothing finite: every cell is "no value".
  const float scale = high > low ? 254.0F / (high - low) : 0.0F;
  cv::Mat codes(values.size(), CV_8U);
  for (int r = 0; r < values.rows; ++r) {
    for (int c = 0; c < values.cols; ++c) {
      const float value = values.at<float>(r, c);
      codes.at<std::uint8_t>(r, c) =
          std::isfinite(value) ? static_cast<std::uint8_t>(1 + std::lround((value - low) * scale)) : 0;
    }
  }
  if (!image_codecs::write(file.string(), codes)) throw std::runtime_error("cannot write '" + file.string() + "'");
  return {{"file", file.filename().string()},
          {"rows", values.rows},
          {"columns", values.cols},
          {"value_min", low},
          {"value_max", high}};
}

}  // namespace

json writeDifferencePictures(const std::string& folder, SequenceView query, SequenceView reference,
                             const std::vector<QueryRecord>& records, int contrast_window) {
  // An earlier evaluation's pictures, which this one may not make, would pass for this one's.
  for (const char* name : {"difference_overview_values.png", "difference_band_values.png"}) {
    std::error_code ignored;
    fs::remove(fs::path(folder) / name, ignored);
  }
  json pictures = {{"contrast_window", contrast_window}};
  if (reference.count <= kOverviewMaxReference) {
    const DifferenceOverview overview =
        differenceOverview(query, reference, contrast_window, kOverviewRows, kOverviewColumns);
    json entry = writeQuantised(overview.values, fs::path(folder) / "difference_overview_values.png");
    entry["query_stride"] = overview.query_stride;
    entry["reference_stride"] = overview.reference_stride;
    pictures["overview"] = entry;
  }
  // The band follows each query's ground truth (the middle of its true frames); queries without
  // any true frame (out of the map) have no band.
  std::vector<const QueryRecord*> with_truth;
  for (const QueryRecord& record : records) {
    if (!record.true_indices.empty()) with_truth.push_back(&record);
  }
  if (!with_truth.empty()) {
    const std::size_t stride = (with_truth.size() + kBandRows - 1) / kBandRows;
    std::vector<int> frames;
    std::vector<int> centres;
    for (std::size_t i = 0; i < with_truth.size(); i += stride) {
      std::vector<int> truth = with_truth[i]->true_indices;
      std::sort(truth.begin(), truth.end());
      frames.push_back(with_truth[i]->query_index);
      centres.push_back(truth[truth.size() / 2]);
    }
    const DifferenceBand band = differenceBand(query, reference, frames, centres, kBandHalfWidth, contrast_window);
    json entry = writeQuantised(band.values, fs::path(folder) / "difference_band_values.png");
    entry["half_width"] = band.half_width;
    entry["query_frames"] = band.query_frames;
    entry["centres"] = band.centres;
    pictures["band"] = entry;
  }
  return pictures;
}

void runPlotTool(const std::vector<std::string>& arguments) {
  // Installed (and relayed in the devel space) next to this executable, with Debian's python3 in its
  // first line: a python3 found first on PATH may lack matplotlib.
  const fs::path tool = fs::read_symlink("/proc/self/exe").parent_path() / "mrs_vpr_plot";
  if (!fs::exists(tool)) throw std::runtime_error("the plotting tool " + tool.string() + " is not installed");
  std::vector<std::string> words = {tool.string()};
  words.insert(words.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& word : words) argv.push_back(word.data());
  argv.push_back(nullptr);
  // Its messages go to stderr: this tool's stdout holds the summary JSON only.
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, STDERR_FILENO, STDOUT_FILENO);
  pid_t child = 0;
  const int spawned = posix_spawn(&child, tool.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) throw std::runtime_error("cannot run " + tool.string() + ": " + std::strerror(spawned));
  int status = 0;
  while (waitpid(child, &status, 0) < 0) {
    if (errno != EINTR) throw std::runtime_error("lost the plotting tool: " + std::string(std::strerror(errno)));
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw std::runtime_error("plotting failed: " + tool.string() + " exited with status " +
                             std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status)));
  }
}

}  // namespace tools
}  // namespace mrs_vpr
