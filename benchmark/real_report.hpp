#pragma once

// The real-data benchmark's tables: each row printed as it is measured, and every row kept for the
// JSON file that mrs_vpr_plot benchmark draws.

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "mrs_vpr/evaluation/evaluation.hpp"

namespace mrs_vpr {
namespace benchmark {

/// What a row of the tables measured, for the JSON output.
struct RowFacts {
  std::string protocol;  ///< "global", "per-frame" or "continuous".
  bool out_of_map = false;
  int reference_frames = 0;
  int sequence_length = 0;
};

class Report {
 public:
  /// Prints the column heads of the rows.
  static void printHeader();

  /// Prints one row and keeps it.
  void row(const std::string& setting, const std::string& method, const EvaluationSummary& summary,
           const RowFacts& facts);

  /// Rows of another shape (printed by their maker), for the JSON output only.
  void add(const std::vector<nlohmann::json>& rows);

  /// Writes `settings` (an object) with every row under "rows" to `path`; nothing when `path` is empty.
  /// Throws std::runtime_error when the file cannot be written.
  void write(const std::string& path, nlohmann::json settings) const;

 private:
  std::vector<nlohmann::json> rows_;
};

}  // namespace benchmark
}  // namespace mrs_vpr
