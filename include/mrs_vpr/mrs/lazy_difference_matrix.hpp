#pragma once

#include <atomic>
#include <optional>
#include <vector>

#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/mrs/temporal_pooling.hpp"

namespace mrs_vpr {

/**
 * Contrast-enhanced difference matrix between a test sequence (rows) and a reference (columns) that
 * computes only the cells a search asks for and remembers them. One hypothesis of the search asks
 * for cells around its trajectory only, so each row keeps one interval of raw differences: the
 * smallest that holds every request (gaps between requests are filled, which near one place costs
 * a few cells). The contrast window sees the same neighbours as enhanceContrast.
 */
class LazyDifferenceMatrix {
 public:
  /// Rows are the `query` cells; column J is the reference cell of `stride` frames ending at frame
  /// J * stride (temporal_pooling.hpp). contrast_window as SequenceParams::contrast_window.
  /// `compact` must outlive the matrix.
  LazyDifferenceMatrix(SequenceView query, SequenceView reference, int stride, const CompactCells& compact,
                       int contrast_window);
  /// Hands the rows' storage to the thread's next matrix (rowStorage).
  ~LazyDifferenceMatrix();
  LazyDifferenceMatrix(const LazyDifferenceMatrix&) = delete;
  LazyDifferenceMatrix& operator=(const LazyDifferenceMatrix&) = delete;

  int rows() const { return query_.count; }
  int columns() const { return reference_.size(); }

  /// Writes the enhanced differences of `row` for columns [begin, end) (inside the matrix) to `out`.
  void enhancedRow(int row, int begin, int end, float* out);

  /// One row's request to enhancedRow.
  struct RowRequest {
    int row;
    int begin;
    int end;
    float* out;
  };
  /// enhancedRow for each request, which must name distinct rows. At stride 1 the cells are the
  /// reference's own frames, so rows share nothing and threads share the requests.
  void enhancedRows(const std::vector<RowRequest>& requests);

  /// Raw descriptor comparisons made so far.
  long long comparisons() const { return comparisons_.load(std::memory_order_relaxed); }

 private:
  /// The raw differences of one row known so far: columns [begin, end), held in `values` from
  /// column `origin` on, with room on both sides so that a growing interval rarely moves.
  struct RowInterval {
    int origin = 0;
    int begin = 0;
    int end = 0;
    std::vector<float> values;
    std::optional<float> first_difference;  ///< At column 0, for enhanceRowSpan; computed on first use.
  };

  /// The storage of the rows of this thread's last matrix. A search builds a matrix for each
  /// hypothesis at each level, with a row for each test cell, and allocating and freeing every row
  /// afresh took about 8% of an MRS query at N = 300; its thread's next matrix reuses them.
  static std::vector<RowInterval>& rowStorage();

  /// Raw differences of `row` over [begin, end), computed where missing; valid until the next call.
  const float* rawRow(int row, int begin, int end);
  /// Computes the raw differences of `row` for columns [begin, end) into `out`.
  void compare(int row, int begin, int end, float* out);

  SequenceView query_;
  PooledReference reference_;
  int contrast_window_;
  std::atomic<long long> comparisons_{0};  ///< Counted by concurrent rows (enhancedRows).
  std::vector<RowInterval> rows_;
};

}  // namespace mrs_vpr
