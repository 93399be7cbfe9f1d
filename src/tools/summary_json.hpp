#pragma once

// An evaluation summary as JSON, in the one spelling that mrs_vpr_eval's --json and the real-data
// benchmark's --json share (mrs_vpr_plot reads both).

#include <cmath>

#include <nlohmann/json.hpp>

#include "mrs_vpr/evaluation/evaluation.hpp"

namespace mrs_vpr {
namespace tools {

/// NaN has no JSON spelling; null says "undefined" (e.g. the median error when nothing was predicted).
inline nlohmann::json numberOrNull(double value) {
  return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

inline nlohmann::json summaryToJson(const EvaluationSummary& summary) {
  return {{"tolerance", summary.tolerance},
          {"queries", summary.queries},
          {"queries_in_map", summary.queries_in_map},
          {"top1", numberOrNull(summary.top1)},
          {"pr_auc", numberOrNull(summary.pr_auc)},
          {"recall_at_100_precision", numberOrNull(summary.recall_at_100_precision)},
          {"accepted", summary.accepted},
          {"accepted_rate", summary.accepted_rate},
          {"accepted_precision", numberOrNull(summary.accepted_precision)},
          {"accepted_recall", numberOrNull(summary.accepted_recall)},
          {"largest_wrong_accepted_error", numberOrNull(summary.largest_wrong_accepted_error)},
          {"median_abs_error", numberOrNull(summary.median_abs_error)},
          {"median_time_ms", numberOrNull(summary.median_time_ms)},
          {"total_time_s", summary.total_time_s}};
}

}  // namespace tools
}  // namespace mrs_vpr
