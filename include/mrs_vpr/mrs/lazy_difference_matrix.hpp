#pragma once

#include <vector>

#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/mrs/temporal_pooling.hpp"

namespace mrs_vpr {

/**
 * Contrast-enhanced difference matrix between a test sequence (rows) and a reference (columns) that
 * computes only the cells a search asks for and remembers them. Each row keeps a few contiguous
 * segments of raw differences, so that nearby requests (particles of one cluster, neighbouring end
 * indices) share work and the contrast window sees the same neighbours as enhanceContrast.
 */
class LazyDifferenceMatrix {
 public:
  /// Rows are the `query` cells; column J is the reference cell of `stride` frames ending at frame
  /// J * stride (temporal_pooling.hpp). contrast_window as SequenceParams::contrast_window.
  /// `frequencies` must outlive the matrix.
  LazyDifferenceMatrix(SequenceView query, SequenceView reference, int stride, const PatchFrequencies& frequencies,
                       int contrast_window);

  int rows() const { return query_.count; }
  int columns() const { return reference_.size(); }

  /// Writes the enhanced differences of `row` for columns [begin, end) (inside the matrix) to `out`.
  void enhancedRow(int row, int begin, int end, float* out);

  /// Raw descriptor comparisons made so far.
  long long comparisons() const { return comparisons_; }

 private:
  struct Segment {
    int begin = 0;
    std::vector<float> values;
    int end() const { return begin + static_cast<int>(values.size()); }
  };

  /// Raw differences of `row` over [begin, end), computed where missing; valid until the next call.
  const float* rawRow(int row, int begin, int end);

  SequenceView query_;
  PooledReference reference_;
  int contrast_window_;
  long long comparisons_ = 0;
  std::vector<std::vector<Segment>> segments_;
  std::vector<double> prefix_;  ///< enhancedRow's prefix sums, kept to avoid an allocation per call.
};

}  // namespace mrs_vpr
