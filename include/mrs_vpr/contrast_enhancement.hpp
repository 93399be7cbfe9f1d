#pragma once

#include <opencv2/core.hpp>

#include "mrs_vpr/query_stop.hpp"

namespace mrs_vpr {

/**
 * OpenSeqSLAM's local contrast enhancement, applied to each row (one query frame) of a CV_32FC1
 * difference matrix: every cell becomes (D - mean) / std over the reference columns
 * [c - window/2, c + window/2] clipped to the matrix (std with n - 1, as MATLAB's std), 0 where the
 * std is 0. The result is shifted by contrastShift(window) so that it is never negative, which
 * OpenSeqSLAM achieves by subtracting the global minimum; a constant shift keeps the live node causal.
 * window == 0 returns a copy of the input.
 */
cv::Mat enhanceContrast(const cv::Mat& differences, int window);

/// The same into `enhanced`, a CV_32FC1 matrix of the differences' size (e.g. kept between queries).
void enhanceContrast(const cv::Mat& differences, int window, cv::Mat& enhanced);

/// The same in place: `matrix` holds the raw differences and gets the enhanced ones, so that a large
/// query needs one matrix, not two. Throws QueryStopped, some rows enhanced, when `stop` asks to stop.
void enhanceContrastInPlace(cv::Mat& matrix, int window, const QueryStop* stop = nullptr);

/// Enhances columns [begin, end) of one row of `columns` raw differences into `out`, exactly as
/// enhanceContrast does, to the bit, from the raw differences their windows see: `raw` holds columns
/// [max(0, begin - window / 2), min(columns, end + window / 2)), and `first_difference` is the row's
/// raw difference at column 0. A search that needs a few cells of a row computes only those, and a
/// row enhanced in pieces (as the map grows) equals the row enhanced whole: the window sums are taken
/// relative to `first_difference`, which every piece of the row shares.
void enhanceRowSpan(const float* raw, int columns, int begin, int end, int window, float first_difference,
                    float* out);

/// Enhances one cell: `values` holds the window's raw differences, `centre` the cell's own.
float enhanceCell(float centre, const float* values, int count, int window);

/// The bound (n - 1) / sqrt(n), n = window + 1, on how negative a z-score over n samples can be.
float contrastShift(int window);

}  // namespace mrs_vpr
