#include "mrs_vpr/evaluation/difference_picture.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>


#include "mrs_vpr/contrast_enhancement.hpp"
#include "mrs_vpr/difference_matrix.hpp"

namespace mrs_vpr {

DifferenceOverview differenceOverview(SequenceView query, SequenceView reference, int contrast_window, int max_rows,
                                      int max_columns) {
  if (query.count < 1 || reference.count < 1) throw std::invalid_argument("difference overview of an empty sequence");
  if (max_rows < 1 || max_columns < 1) throw std::invalid_argument("difference overview needs at least one cell");
  DifferenceOverview overview;
  overview.query_stride = (query.count + max_rows - 1) / max_rows;
  overview.reference_stride = (reference.count + max_columns - 1) / max_columns;
  const SequenceView rows = query.subsample(0, overview.query_stride);
  // Enhanced at full resolution, as the methods see it, then pooled: pooling first would blur the
  // local contrast that makes a place stand out.
  cv::Mat full = computeDifferenceMatrix(rows, reference);
  enhanceContrastInPlace(full, contrast_window);
  const int columns = (reference.count + overview.reference_stride - 1) / overview.reference_stride;
  overview.values.create(rows.count, columns, CV_32F);
  for (int c = 0; c < columns; ++c) {
    const int begin = c * overview.reference_stride;
    const int end = std::min(reference.count, begin + overview.reference_stride);
    cv::reduce(full.colRange(begin, end), overview.values.col(c), 1, cv::REDUCE_MIN);
  }
  return overview;
}

DifferenceBand differenceBand(SequenceView query, SequenceView reference, const std::vector<int>& query_frames,
                              const std::vector<int>& centres, int half_width, int contrast_window) {
  if (query_frames.size() != centres.size()) {
    throw std::invalid_argument("difference band: " + std::to_string(query_frames.size()) + " query frames but " +
                                std::to_string(centres.size()) + " centres");
  }
  if (half_width < 0) throw std::invalid_argument("difference band: half width must be >= 0");
  DifferenceBand band;
  band.query_frames = query_frames;
  band.centres = centres;
  band.half_width = half_width;
  const int width = 2 * half_width + 1;
  band.values = cv::Mat(static_cast<int>(query_frames.size()), width, CV_32F,
                        cv::Scalar(std::numeric_limits<float>::quiet_NaN()));
  // Each row's segment reaches half a contrast window beyond the band, so that every cell of the band
  // is enhanced over the same reference frames as in the whole matrix.
  const int margin = contrast_window / 2;
  for (std::size_t r = 0; r < query_frames.size(); ++r) {
    const int frame = query_frames[r];
    if (frame < 0 || frame >= query.count) {
      throw std::invalid_argument("difference band: query frame " + std::to_string(frame) + " outside 0.." +
                                  std::to_string(query.count - 1));
    }
    const int first = centres[r] - half_width;
    const int begin = std::max(0, first - margin);
    const int end = std::min(reference.count, first + width + margin);
    if (begin >= end) continue;
    const cv::Mat segment =
        enhanceContrast(computeDifferenceMatrix(query.slice(frame, frame + 1), reference.slice(begin, end)),
                        contrast_window);
    const int from = std::max(first, 0);
    const int to = std::min(first + width, reference.count);
    if (from >= to) continue;
    segment.colRange(from - begin, to - begin)
        .copyTo(band.values.row(static_cast<int>(r)).colRange(from - first, to - first));
  }
  return band;
}

}  // namespace mrs_vpr
