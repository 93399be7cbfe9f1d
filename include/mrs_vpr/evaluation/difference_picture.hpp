#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "mrs_vpr/descriptor_sequence.hpp"

namespace mrs_vpr {

/**
 * A small picture of the whole difference matrix, for plots: row r is query frame r * query_stride,
 * column c the lowest difference among reference frames [c * reference_stride, (c + 1) * reference_stride)
 * (the lowest, so that a match one frame wide is not averaged away).
 */
struct DifferenceOverview {
  cv::Mat values;  ///< CV_32FC1, rows x columns.
  int query_stride = 1;
  int reference_stride = 1;
};

/**
 * The difference matrix of `query` against `reference` (contrast-enhanced over `contrast_window`
 * reference frames as the methods see it; 0 = raw), at most max_rows x max_columns: query frames are
 * sampled, reference frames pooled by their minimum. Costs (query frames / query_stride) x reference frames
 * descriptor differences. Throws std::invalid_argument on empty input, max_rows or max_columns < 1
 * or descriptors of different sizes.
 */
DifferenceOverview differenceOverview(SequenceView query, SequenceView reference, int contrast_window, int max_rows,
                                      int max_columns);

/**
 * The difference matrix along a path through it, for maps too big for an overview: row r holds the
 * reference frames centres[r] - half_width .. centres[r] + half_width for query frame
 * query_frames[r], contrast-enhanced as in the full matrix. Cells outside the reference are NaN.
 */
struct DifferenceBand {
  cv::Mat values;  ///< CV_32FC1, query_frames.size() x (2 * half_width + 1).
  std::vector<int> query_frames;
  std::vector<int> centres;
  int half_width = 0;
};

/// Throws std::invalid_argument when the two lists differ in length, a frame lies outside its
/// sequence, half_width < 0 or descriptors differ in size.
DifferenceBand differenceBand(SequenceView query, SequenceView reference, const std::vector<int>& query_frames,
                              const std::vector<int>& centres, int half_width, int contrast_window);

}  // namespace mrs_vpr
