#pragma once

#include <limits>
#include <vector>

#include "mrs_vpr/mrs/lazy_difference_matrix.hpp"
#include "mrs_vpr/mrs/sampling_level.hpp"
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
  /// Ends scored on demand over `velocities`; `matrix` must outlive the table. With `look_ahead`, a
  /// window's unknown ends are computed together with the unknown ends up to a radius beyond it:
  /// where cells are cheap (pooled levels) one wider request per row then serves the particle's next
  /// window too, instead of a second narrow one.
  EndCostTable(LazyDifferenceMatrix& matrix, const SamplingLevel& level, std::vector<double> velocities,
               bool look_ahead = false);

  /// The best end within `radius` of `centre` (the paper's +-Id_shift window).
  Evaluation bestInWindow(int centre, int radius);
  /// Costs of every end; infinity where none was computed or no trajectory fits.
  const std::vector<float>& costs() const { return costs_.cost; }
  /// Velocity of the best trajectory through end `index` (where it was computed).
  float velocityAt(int index) const { return costs_.velocity[static_cast<std::size_t>(index)]; }

 private:
  void computeEnds(int first, int last);

  LazyDifferenceMatrix* matrix_ = nullptr;
  SamplingLevel level_;
  std::vector<double> velocities_;
  std::vector<std::vector<int>> offsets_;  ///< offsets_[v][r]: row r's column offset at velocity v.
  AnchorCosts costs_;
  std::vector<char> known_;
  bool look_ahead_ = false;
};

/**
 * How far either side of the previous level's velocity a finer level searches. A level of L rows
 * tells velocities apart to about 1 / L (one cell of drift over the sequence), so the fan reaches
 * +-2 / L around it and narrows level by level; but at least a few steps of the velocity grid:
 * two right after the coarsest level, whose short sequence can miss the velocity by two steps, one
 * once a finer level has refined it. On Nordland with steps 0.1, 0.05 and 0.02 and N = 64 to 300,
 * one step after the coarsest level lost up to 1.5 points; one step after a finer level lost
 * nothing and saved a fifth to a third of the comparisons at N = 300.
 */
double fanSpread(double velocity_step, int previous_rows, bool after_coarsest);

/// The velocities of `all` within `spread` of `centre`; the nearest one when none is.
std::vector<double> velocitiesNear(const std::vector<double>& all, double centre, double spread);

}  // namespace mrs_vpr
