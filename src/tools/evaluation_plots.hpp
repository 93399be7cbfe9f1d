#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/evaluation/evaluation.hpp"

namespace mrs_vpr {
namespace tools {

/**
 * Writes into `folder` the small pictures of the difference matrix that the plots draw on: the whole
 * matrix downsampled (maps of at most 20000 frames) and the band around the ground truth (queries
 * with ground truth). Each is an 8-bit PNG (0 = no value, 1..255 = value_min..value_max); the
 * returned JSON describes them for mrs_vpr_plot.
 */
nlohmann::ordered_json writeDifferencePictures(const std::string& folder, SequenceView query, SequenceView reference,
                                               const std::vector<QueryRecord>& records, int contrast_window);

/**
 * Runs mrs_vpr_plot (installed next to this executable) with `arguments`, its output passed through.
 * Throws std::runtime_error when it cannot be started or fails.
 */
void runPlotTool(const std::vector<std::string>& arguments);

}  // namespace tools
}  // namespace mrs_vpr
