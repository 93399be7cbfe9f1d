#pragma once

// --diagnose: where MRS kept the truth of known-ground queries, level by level.

#include <map>
#include <string>
#include <vector>

#include "mrs_vpr/mrs/level_trace.hpp"

namespace mrs_vpr {
namespace benchmark {

/// Per level, how often a hypothesis lay within tolerance of the truth and at which rank; for the
/// coarsest level also the rank among the distinct minima of its table.
class TruthDiagnosis {
 public:
  /// Counts one query's trace; `truth` holds its true reference indices.
  void add(const std::vector<MrsLevelTrace>& trace, const std::vector<int>& truth, int tolerance,
           double accept_threshold);

  /// Prints the counts, each line headed by `setting`.
  void print(const std::string& setting) const;

 private:
  struct LevelCounts {
    int stride = 1;
    int queries = 0;
    std::map<int, int> ranks;        ///< rank (1-based; 0 = lost) -> queries
    std::map<int, int> table_ranks;  ///< the same among the coarse table's minima
  };

  std::vector<LevelCounts> levels_;
  int confidently_wrong_ = 0;
};

}  // namespace benchmark
}  // namespace mrs_vpr
