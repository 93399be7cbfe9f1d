#pragma once

// The real-data benchmark's command line.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mrs_vpr/parameters.hpp"

namespace mrs_vpr {
namespace benchmark {

/// What to measure, and the settings to explore (the search and drive settings default to the core's).
struct RealBenchmarkOptions {
  std::string data;
  std::string part = "check";
  int queries = 100;
  std::vector<int> lengths = {100, 200, 300};
  std::vector<int> per_frame_lengths = {10, 50};  ///< ds of the per-frame rows
  std::vector<std::string> references = {"1.8k", "9k"};
  int threads = 1;
  int tolerance = 5;
  std::uint64_t seed = 42;
  bool per_frame = true;
  bool global = true;
  bool drives = true;
  int drive_length = 0;
  int drive_alignment_slack = SequenceParams{}.alignment_slack;
  double drive_accept_threshold = SequenceParams{}.accept_threshold;
  double drive_min_appearance_change = RecognizerParams{}.min_appearance_change;
  std::string drive_alignment = toString(SequenceParams{}.alignment);
  std::string drive_queries = "each";  // as the node asks
  int drive_seeds = 1;                 // drives of seeds seed .. seed + drive_seeds - 1
  bool diagnose = false;
  std::string json;  ///< Every row of the tables also goes to this file (for mrs_vpr_plot benchmark).
  int hypotheses = MrsParams{}.hypotheses;
  int min_coarse_frames = MrsParams{}.min_coarse_frames;
  double velocity_min = SequenceParams{}.velocity_min;
  double velocity_max = SequenceParams{}.velocity_max;
  std::vector<std::string> methods = {"seqslam", "mrs"};
  DescriptorParams descriptor;
};

/// Parses and checks the command line; returns nothing after printing the help. Throws
/// std::invalid_argument (naming the option) for a bad value, before any frame is read.
std::optional<RealBenchmarkOptions> parseRealBenchmarkOptions(int argc, char** argv);

}  // namespace benchmark
}  // namespace mrs_vpr
