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

/// The best end within `radius` of `centre` in a table of costs already computed for every end.
Evaluation bestInWindow(const AnchorCosts& costs, int centre, int radius, const SamplingLevel& level);

/**
 * The best end within `radius` of `centre` over the given velocities, computing (through `matrix`)
 * only the cells those trajectories visit. The cost is the mean difference along the trajectory, so
 * costs of levels with different numbers of rows mean the same.
 */
Evaluation evaluateTrajectories(LazyDifferenceMatrix& matrix, const SamplingLevel& level, int centre, int radius,
                                const std::vector<double>& velocities);

/// The velocities of `all` within `spread` of `centre`; the nearest one when none is.
std::vector<double> velocitiesNear(const std::vector<double>& all, double centre, double spread);

}  // namespace mrs_vpr
