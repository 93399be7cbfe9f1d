#pragma once

// mrs_vpr_eval's command line: its options, parsed and checked before any frame is read.

#include <cstdint>
#include <optional>
#include <string>

#include "mrs_vpr/evaluation/evaluation.hpp"
#include "mrs_vpr/parameters.hpp"

namespace mrs_vpr {
namespace tools {

/// What an evaluation is asked to do.
struct EvalOptions {
  std::string reference;
  std::string query;
  std::string topic;
  std::string ground_truth;
  std::string method;
  std::string protocol;
  std::string output;
  std::string plots;
  int queries = kDefaultGlobalQueries;
  int tolerance = kDefaultTolerance;
  int threads = 0;
  bool out_of_map = false;
  // Signed, so that a negative seed is seen and refused, not wrapped.
  std::int64_t seed = static_cast<std::int64_t>(MrsParams{}.seed);
  Parameters params;
  bool descriptor_given = false;  ///< A descriptor option was set; else a map database's own front end is used.
  /// As the node's ~min_appearance_change: both traversals are keyframed as the node keyframes a camera.
  double min_appearance_change = RecognizerParams{}.min_appearance_change;
  bool min_appearance_change_given = false;  ///< Else a map database's own keyframing, where it records one.
};

/// Parses and checks the command line; returns nothing after printing the help. Throws
/// std::invalid_argument or std::runtime_error naming the option at fault, before any frame is read:
/// results that could not be written are found before the evaluation rather than after it.
std::optional<EvalOptions> parseEvalOptions(int argc, char** argv);

}  // namespace tools
}  // namespace mrs_vpr
