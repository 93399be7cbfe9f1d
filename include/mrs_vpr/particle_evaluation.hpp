#pragma once

#include <limits>
#include <vector>

#include "mrs_vpr/lazy_difference_matrix.hpp"
#include "mrs_vpr/sampling_level.hpp"
#include "mrs_vpr/trajectory_search.hpp"

namespace mrs_vpr {

/// Where a particle should move: the best end near it, its cost and velocity (Algorithm 2).
struct Evaluation {
  int index = -1;  ///< -1 when no trajectory fits.
  float cost = std::numeric_limits<float>::infinity();
  float velocity = 1.0F;
};

/**
 * Trajectory costs of the ends of one level (mean difference along the best straight trajectory,
 * so that levels with different numbers of rows mean the same), each computed at most once: all at
 * once from a dense table, or on demand through a lazy difference matrix, where particles that
 * share ends share the work.
 */
class EndCostTable {
 public:
  /// Every end already scored (the dense coarsest level).
  EndCostTable(AnchorCosts costs, const SamplingLevel& level);
  /// Ends scored on demand over `velocities`; `matrix` must outlive the table.
  EndCostTable(LazyDifferenceMatrix& matrix, const SamplingLevel& level, std::vector<double> velocities);

  /// The best end within `radius` of `centre` (the paper's +-Id_shift window).
  Evaluation bestInWindow(int centre, int radius);
  /// Costs of every end; infinity where none was computed or no trajectory fits.
  const std::vector<float>& costs() const { return costs_.cost; }

 private:
  void computeEnds(int first, int last);

  LazyDifferenceMatrix* matrix_ = nullptr;
  SamplingLevel level_;
  std::vector<double> velocities_;
  std::vector<std::vector<int>> offsets_;  ///< offsets_[v][r]: row r's column offset at velocity v.
  AnchorCosts costs_;
  std::vector<char> known_;
};

/// The velocities of `all` within `spread` of `centre`; the nearest one when none is.
std::vector<double> velocitiesNear(const std::vector<double>& all, double centre, double spread);

}  // namespace mrs_vpr
