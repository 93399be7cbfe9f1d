#include "mrs_vpr/mrs/lazy_difference_matrix.hpp"

#include <algorithm>
#include <cstring>

#include <opencv2/core/utility.hpp>

#include "mrs_vpr/contrast_enhancement.hpp"
#include "mrs_vpr/difference_matrix.hpp"

namespace mrs_vpr {
namespace {

// Room kept on either side of a row's interval, in cells: a hypothesis moves a few cells per step,
// so its later requests extend the interval in place.
constexpr int kRoom = 32;
// Rows kept for the thread's next matrix hold at most this much: a very long query's rows are freed.
constexpr std::size_t kKeptRowBytes = 8UL * 1024 * 1024;

}  // namespace

LazyDifferenceMatrix::LazyDifferenceMatrix(SequenceView query, SequenceView reference, int stride,
                                           const CompactCells& compact, int contrast_window)
    : query_(query), reference_(reference, stride, compact), contrast_window_(contrast_window) {
  rows_.swap(rowStorage());
  if (rows_.size() < static_cast<std::size_t>(query.count)) rows_.resize(static_cast<std::size_t>(query.count));
  for (int row = 0; row < query.count; ++row) {
    RowInterval& interval = rows_[static_cast<std::size_t>(row)];
    interval.values.clear();  // Nothing known; the capacity stays.
    interval.first_difference.reset();
  }
}

LazyDifferenceMatrix::~LazyDifferenceMatrix() {
  std::size_t bytes = 0;
  for (const RowInterval& interval : rows_) bytes += interval.values.capacity() * sizeof(float);
  std::vector<RowInterval>& kept = rowStorage();
  if (bytes <= kKeptRowBytes && kept.size() < rows_.size()) kept.swap(rows_);
}

std::vector<LazyDifferenceMatrix::RowInterval>& LazyDifferenceMatrix::rowStorage() {
  thread_local std::vector<RowInterval> storage;
  return storage;
}

void LazyDifferenceMatrix::compare(int row, int begin, int end, float* out) {
  const std::uint8_t* test_frame = query_.frame(row);
  while (begin < end) {
    const PooledReference::Run run = reference_.run(begin, end - begin);
    descriptorDifferences(test_frame, run.cells, run.pitch, run.count, query_.descriptor_size, out);
    comparisons_.fetch_add(run.count, std::memory_order_relaxed);
    begin += run.count;
    out += run.count;
  }
}

const float* LazyDifferenceMatrix::rawRow(int row, int begin, int end) {
  RowInterval& interval = rows_[static_cast<std::size_t>(row)];
  if (interval.values.empty()) {  // Nothing known yet: an empty interval at the request's start.
    interval.origin = begin;
    interval.begin = begin;
    interval.end = begin;
  }
  const int new_begin = std::min(begin, interval.begin);
  const int new_end = std::max(end, interval.end);
  const int capacity_end = interval.origin + static_cast<int>(interval.values.size());
  if (new_begin < interval.origin || new_end > capacity_end) {
    // Out of room: move the known values to where they belong with room again on both sides, in
    // the row's own storage (which an earlier matrix of this thread may have sized already).
    const int origin = std::max(0, new_begin - kRoom);
    const auto size = static_cast<std::size_t>(std::min(columns(), new_end + kRoom) - origin);
    std::vector<float>& values = interval.values;
    if (values.size() < size) values.resize(size);
    const auto known = static_cast<std::size_t>(interval.end - interval.begin);
    if (known > 0) {
      std::memmove(values.data() + (interval.begin - origin), values.data() + (interval.begin - interval.origin),
                   known * sizeof(float));
    }
    values.resize(size);
    interval.origin = origin;
  }
  float* values = interval.values.data();  // values[c - origin] for column c.
  compare(row, new_begin, interval.begin, values + (new_begin - interval.origin));
  compare(row, interval.end, new_end, values + (interval.end - interval.origin));
  interval.begin = new_begin;
  interval.end = new_end;
  return values + (begin - interval.origin);
}

void LazyDifferenceMatrix::enhancedRow(int row, int begin, int end, float* out) {
  // The same clipped windows as enhanceContrast.
  const int half = contrast_window_ / 2;
  const int raw_begin = std::max(0, begin - half);
  const float* raw = rawRow(row, raw_begin, std::min(columns(), end + half));
  RowInterval& interval = rows_[static_cast<std::size_t>(row)];
  if (!interval.first_difference && contrast_window_ > 0) {
    // Every piece of the row is enhanced relative to its difference at column 0: known when the row
    // starts there, else one comparison more.
    float first_difference = raw[0];
    if (raw_begin > 0) compare(row, 0, 1, &first_difference);
    interval.first_difference = first_difference;
  }
  enhanceRowSpan(raw, columns(), begin, end, contrast_window_, interval.first_difference.value_or(0.0F), out);
}

void LazyDifferenceMatrix::enhancedRows(const std::vector<RowRequest>& requests) {
  const auto serve = [&](const cv::Range& range) {
    for (int i = range.start; i < range.end; ++i) {
      const RowRequest& request = requests[static_cast<std::size_t>(i)];
      enhancedRow(request.row, request.begin, request.end, request.out);
    }
  };
  const cv::Range all(0, static_cast<int>(requests.size()));
  // Pooled cells are computed on first use into shared storage: one thread then.
  if (reference_.stride() == 1) {
    cv::parallel_for_(all, serve);
  } else {
    serve(all);
  }
}

}  // namespace mrs_vpr
