#pragma once

#include <functional>
#include <vector>

#include <opencv2/core.hpp>

#include "mrs_vpr/trajectory_search.hpp"

namespace mrs_vpr {

/// Fills `raw` (CV_32FC1, every row of the matrix x (end - begin)) with the raw differences of
/// columns [begin, end).
using DifferenceTile = std::function<void(int begin, int end, cv::Mat& raw)>;

/**
 * costsByAnchor(enhanceContrast(D, contrast_window), rows, velocities) for a difference matrix D of
 * `columns` columns that is never held whole: anchors are scored a tile at a time from the columns
 * their trajectories and contrast windows reach, filled by `tile`. A tile's buffers (a few hundred
 * KB) stay in the cache from the differences to the sums, and a map of a million frames needs no
 * matrix of 75 MB per query. Tiles overlap by the trajectories' reach, about a tenth more cells.
 * Tiles are fixed, not split by thread, so the costs do not depend on the number of threads; they
 * equal the whole matrix's to the bit (each row's pieces are enhanced relative to its difference at
 * column 0, which `tile` gives once for all rows).
 */
AnchorCosts tiledCostsByAnchor(int columns, const SequenceRows& rows, const std::vector<double>& velocities,
                               int contrast_window, const DifferenceTile& tile, const QueryStop* stop = nullptr);

/// The same into `costs`, whose storage is reused: a search that keeps it between queries does not
/// fault in a map-sized table (8 MB at a million frames) per query. Each thread keeps its tile buffers.
/// Throws QueryStopped when `stop` asks to (checked before each tile).
void tiledCostsByAnchor(int columns, const SequenceRows& rows, const std::vector<double>& velocities,
                        int contrast_window, const DifferenceTile& tile, AnchorCosts& costs,
                        const QueryStop* stop = nullptr);

}  // namespace mrs_vpr
