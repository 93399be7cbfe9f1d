#pragma once

#include <vector>

namespace mrs_vpr {

/// What the search kept at one level of one query: where the truth was lost, if it was.
struct MrsLevelTrace {
  int stride = 1;
  /// Reference frames (end of each cell) of the level's hypotheses when it ended, lowest cost first.
  std::vector<int> candidates;
  /// Coarsest level only: the distinct minima of its table of every end, lowest cost first (at most
  /// kTracedMinima), i.e. the ranking the search could have had before any particle moved.
  std::vector<int> table_minima;
  /// Coarsest level only: the confidence the table alone gives its lowest minimum.
  float table_confidence = 0.0F;
  static constexpr int kTracedMinima = 50;
};

}  // namespace mrs_vpr
