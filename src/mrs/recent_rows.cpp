#include "mrs_vpr/mrs/recent_rows.hpp"

#include <algorithm>
#include <iterator>
#include <stdexcept>
#include <string>
#include <utility>

#include <opencv2/core/utility.hpp>

#include "mrs_vpr/contrast_enhancement.hpp"
#include "mrs_vpr/difference_matrix.hpp"

namespace mrs_vpr {
namespace {

// Cells of a row enhanced as one piece of work.
constexpr int kStretch = 16384;

}  // namespace

RecentRows::RecentRows(int contrast_window, int max_rows) : contrast_window_(contrast_window), max_rows_(max_rows) {
  if (contrast_window_ < 0) throw std::invalid_argument("contrast_window must not be negative");
}

int RecentRows::finalEnd(int frames) const {
  return contrast_window_ == 0 ? frames : std::max(0, frames - contrast_window_ / 2);
}

long long RecentRows::extend(SequenceView map, const std::vector<std::pair<int, Row*>>& rows) const {
  const int final_end = finalEnd(map.count);
  const int half = contrast_window_ / 2;
  const auto frames = static_cast<std::size_t>(map.count);
  // Rows final up to the same cell need the same raw columns: one difference matrix each, so that the
  // map streams through the cache once for all of them, as in the brute force.
  // A map of at most half a contrast window has no final cell, yet a row must cover every frame: there
  // the rows are sized and given their first difference as the map grows.
  std::map<int, std::vector<std::pair<int, Row*>>> by_final_end;
  for (const auto& entry : rows) {
    const Row& row = *entry.second;
    if (row.final_end < final_end || row.values.size() < frames) by_final_end[row.final_end].push_back(entry);
  }
  long long comparisons = 0;
  for (const auto& entry : by_final_end) {
    const int old_end = entry.first;  // Named here: C++17 lambdas cannot capture structured bindings.
    const std::vector<std::pair<int, Row*>>& group = entry.second;
    // enhanceRowSpan reads the raw cells its windows see.
    const int raw_begin = std::max(0, old_end - half);
    const int raw_end = std::min(map.count, final_end + half);
    DescriptorSequence test_frames(map.descriptor_size);
    test_frames.reserve(static_cast<int>(group.size()));
    for (const auto& test_row : group) {
      test_frames.append(
          cv::Mat(1, map.descriptor_size, CV_8U, const_cast<std::uint8_t*>(map.frame(test_row.first))));
    }
    cv::Mat raw(static_cast<int>(group.size()), raw_end - raw_begin, CV_32F);
    computeDifferenceMatrix(test_frames.view(), map.slice(raw_begin, raw_end), raw);
    comparisons += static_cast<long long>(raw.total());
    for (std::size_t k = 0; k < group.size(); ++k) {
      Row& row = *group[k].second;
      if (old_end == 0) row.first_difference = raw.at<float>(static_cast<int>(k), 0);  // New: raw from column 0.
      // Room to grow, so that the row is not copied at every new frame.
      if (row.values.capacity() < frames) row.values.reserve(frames + frames / 8);
      if (row.values.size() < frames) row.values.resize(frames);
      row.final_end = final_end;
    }
    // Stretches of every row enhanced in parallel: a single new row is most of a question's work.
    const int stretches = (final_end - old_end + kStretch - 1) / kStretch;
    cv::parallel_for_(cv::Range(0, raw.rows * stretches), [&](const cv::Range& part) {
      for (int k = part.start; k < part.end; ++k) {
        const int begin = old_end + (k % stretches) * kStretch;
        const int end = std::min(final_end, begin + kStretch);
        const float* seen = raw.ptr<float>(k / stretches) + (std::max(0, begin - half) - raw_begin);
        Row& row = *group[static_cast<std::size_t>(k / stretches)].second;
        enhanceRowSpan(seen, map.count, begin, end, contrast_window_, row.first_difference,
                       row.values.data() + begin);
      }
    });
  }
  return comparisons;
}

void RecentRows::requireInside(SequenceView map, int first, int count, int columns) const {
  if (first < 0 || count < 1 || first + count > map.count || columns < 1 || columns > map.count) {
    throw std::invalid_argument("RecentRows: frames [" + std::to_string(first) + ", " + std::to_string(first + count) +
                                ") against " + std::to_string(columns) + " columns lie outside a map of " +
                                std::to_string(map.count) + " frames");
  }
}

void RecentRows::forgetStaleLocked(SequenceView map, int first, int count) {
  // A map that shrank was emptied or replaced: its rows describe other frames.
  const bool shrank = !rows_.empty() && (rows_.rbegin()->first >= map.count ||
                                          rows_.rbegin()->second.final_end > finalEnd(map.count));
  if (shrank) rows_.clear();
  if (map.count < asked_map_size_) asked_newest_ = -1;
  // The longest question keeps its rows until the map has grown by max_rows_ frames since it was asked.
  if (count >= kept_rows_ || map.count - kept_since_ > max_rows_ || map.count < kept_since_) {
    kept_rows_ = std::min(max_rows_, count);
    kept_since_ = map.count;
  }
  rows_.erase(rows_.begin(), rows_.lower_bound(std::min(first, map.count - kept_rows_)));
}

int RecentRows::missingRowsLocked(int first, int count) const {
  int missing = 0;
  for (int frame = first; frame < first + count; ++frame) missing += rows_.count(frame) == 0 ? 1 : 0;
  return missing;
}

bool RecentRows::keepsPaceLocked(int first, int count) const {
  int newest_known = asked_newest_ >= first && asked_newest_ < first + count ? asked_newest_ : -1;
  const auto after_rows = rows_.lower_bound(first + count);
  if (after_rows != rows_.begin()) {
    const int newest_row = std::prev(after_rows)->first;
    if (newest_row >= first) newest_known = std::max(newest_known, newest_row);
  }
  return newest_known >= 0 && first + count - 1 - newest_known <= count / kMissingRowsShare;
}

std::unique_lock<std::mutex> RecentRows::lockFresh(SequenceView map, int first, int count) {
  requireInside(map, first, count, map.count);
  std::unique_lock<std::mutex> lock(mutex_);
  forgetStaleLocked(map, first, count);
  countBytesLocked();  // Rows may have been dropped.
  return lock;
}

int RecentRows::missingRows(SequenceView map, int first, int count) {
  const auto lock = lockFresh(map, first, count);
  return missingRowsLocked(first, count);
}

bool RecentRows::keepsPace(SequenceView map, int first, int count) {
  const auto lock = lockFresh(map, first, count);
  return keepsPaceLocked(first, count);
}

bool RecentRows::readsRows(SequenceView map, int first, int count) {
  const auto lock = lockFresh(map, first, count);
  return missingRowsLocked(first, count) <= count / kMissingRowsShare || keepsPaceLocked(first, count);
}

void RecentRows::noteAsked(SequenceView map, int first, int count) {
  requireInside(map, first, count, map.count);
  std::lock_guard<std::mutex> lock(mutex_);
  asked_newest_ = first + count - 1;
  asked_map_size_ = map.count;
}

long long RecentRows::costs(SequenceView map, int first, int count, int columns, const SequenceRows& rows,
                            const std::vector<double>& velocities, AnchorCosts& costs) {
  if (!covers(count)) {
    throw std::invalid_argument("RecentRows: " + std::to_string(count) + " test frames, at most " +
                                std::to_string(max_rows_) + " kept");
  }
  requireInside(map, first, count, columns);  // The columns too: lockFresh checks the frames only.
  const auto lock = lockFresh(map, first, count);
  try {
    return costsLocked(map, first, count, columns, rows, velocities, costs);
  } catch (...) {
    // A row left part-extended, or holding this query's tail, would give wrong costs to every later
    // question: the rows are only a cache, so they are all computed again.
    rows_.clear();
    countBytesLocked();
    throw;
  }
}

long long RecentRows::costsLocked(SequenceView map, int first, int count, int columns, const SequenceRows& rows,
                                  const std::vector<double>& velocities, AnchorCosts& costs) {
  std::vector<std::pair<int, Row*>> test_rows;
  for (int frame = first; frame < first + count; ++frame) test_rows.emplace_back(frame, &rows_[frame]);
  // Continuous mode asks about each keyframe since its last question, oldest first, and every later
  // question's test frames include the keyframes after this one's: their rows join this pass over the
  // map, which reading the map bounds, rather than each paying for a pass of its own. At most as many
  // as a question may miss and still read the rows.
  std::vector<std::pair<int, Row*>> extended = test_rows;
  const int newer_end = std::min(map.count, first + count + std::min(count / kMissingRowsShare, max_rows_ - count));
  for (int frame = first + count; frame < newer_end; ++frame) extended.emplace_back(frame, &rows_[frame]);
  long long comparisons = extend(map, extended);

  // The reference ends at `columns`: the cells whose contrast window that end clips are enhanced for
  // this query, over the final ones, which are put back afterwards.
  const int tail_begin = finalEnd(columns);
  const auto tail = static_cast<std::ptrdiff_t>(columns - tail_begin);
  const int half = contrast_window_ / 2;
  std::vector<float> final_tails(static_cast<std::size_t>(count * tail));
  std::vector<const float*> row_data;
  std::vector<float> raw;
  for (int i = 0; i < count; ++i) {
    float* values = test_rows[static_cast<std::size_t>(i)].second->values.data();
    row_data.push_back(values);
    if (tail == 0) continue;
    std::copy(values + tail_begin, values + columns, final_tails.begin() + i * tail);
    const int raw_begin = std::max(0, tail_begin - half);
    raw.resize(static_cast<std::size_t>(columns - raw_begin));
    descriptorDifferences(map.frame(first + i), map.frame(raw_begin), map.pitch(), columns - raw_begin,
                          map.descriptor_size, raw.data());
    comparisons += columns - raw_begin;
    const float first_difference = test_rows[static_cast<std::size_t>(i)].second->first_difference;
    enhanceRowSpan(raw.data(), columns, tail_begin, columns, contrast_window_, first_difference,
                   values + tail_begin);
  }
  costsByAnchor(row_data, columns, rows, velocities, costs);
  for (int i = 0; i < count && tail > 0; ++i) {
    const auto kept = final_tails.begin() + i * tail;
    std::copy(kept, kept + tail, test_rows[static_cast<std::size_t>(i)].second->values.data() + tail_begin);
  }
  countBytesLocked();
  return comparisons;
}

void RecentRows::clear() {
  std::lock_guard<std::mutex> lock(mutex_);
  rows_.clear();
  kept_rows_ = 0;
  kept_since_ = 0;
  asked_newest_ = -1;
  asked_map_size_ = 0;
  bytes_ = 0;
}

void RecentRows::countBytesLocked() {
  std::size_t bytes = 0;
  for (const auto& entry : rows_) bytes += entry.second.values.capacity() * sizeof(float);
  bytes_ = bytes;
}

int RecentRows::rowCount() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return static_cast<int>(rows_.size());
}

}  // namespace mrs_vpr
