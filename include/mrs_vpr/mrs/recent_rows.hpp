#pragma once

#include <atomic>
#include <cstddef>
#include <map>
#include <mutex>
#include <utility>
#include <vector>

#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/trajectory_search.hpp"

namespace mrs_vpr {

/// Rows a PlaceRecognizer keeps at most: test sequences of up to this many frames reuse them. Each
/// holds 4 bytes a map frame (4 MB at a million frames). Continuous mode asks sequence_length frames.
constexpr int kMaxRecentRows = 128;

/// MRS reads kept rows when at most 1 / kMissingRowsShare of a test sequence's frames lack one
/// (their rows cost that share of the brute force's differences), and searches otherwise.
constexpr int kMissingRowsShare = 4;

/**
 * The contrast-enhanced rows of the difference matrix for the map's own newest frames, kept between
 * queries: test sequences of them (matchRecent, continuous mode) ask again and again about mostly the
 * same frames. A frame's row, its differences to every map frame, is computed when a query first
 * includes the frame and extended as the map grows, instead of again at every query. A query then
 * only sums trajectories through rows it already has, and every end's cost is the brute force's.
 *
 * A cell of a row is final once the map reaches half a contrast window beyond it; the few cells the
 * end of a query's reference clips are enhanced for that query alone. Rows are kept for the newest
 * frames, as many as the longest test sequence asked, at most `max_rows`, until the map has grown by
 * `max_rows` frames since that question: then as many as the question being asked. So one long
 * `~query` among continuous mode's short ones does not keep its rows (4 bytes a map frame each) for
 * good, and long questions asked again and again keep theirs. Thread-safe: queries that use the rows
 * take turns.
 */
class RecentRows {
 public:
  RecentRows(int contrast_window, int max_rows);

  /// Whether a test sequence of `count` frames may use kept rows.
  bool covers(int count) const { return count >= 1 && count <= max_rows_; }

  /**
   * costsByAnchor(enhanceContrast(D, contrast_window), rows, velocities) into `costs`, for the
   * difference matrix D of map frames [first, first + count) against map frames [0, columns): the
   * brute force's costs, to the bit. `map` is the whole map;
   * rows of frames it no longer holds are dropped. The rows of up to count / kMissingRowsShare map
   * frames after the test frames are computed in the same pass over the map: the next questions of
   * continuous mode, which asks about each new keyframe in turn, read them. Returns the descriptor
   * comparisons made. Throws std::invalid_argument when the frames or columns lie outside `map`; when
   * anything else throws (std::bad_alloc), every row is forgotten, so that none stays half computed.
   */
  long long costs(SequenceView map, int first, int count, int columns, const SequenceRows& rows,
                  const std::vector<double>& velocities, AnchorCosts& costs);

  /// Test frames among map frames [first, first + count) that have no row yet. Their rows cost as
  /// much as the brute force's differences, so a caller may prefer another search when most are missing.
  int missingRows(SequenceView map, int first, int count);
  /**
   * Whether questions come often enough for the rows to keep up: the newest of the test frames that
   * has a row, or that the last question asked about (noteAsked), is followed by at most count /
   * kMissingRowsShare of them. Then the rows the test frames lack (from before the questions began)
   * are worth computing, once, in one pass over the map, and afterwards each question adds only the
   * frames that are new. Otherwise they would cost a good part of the brute force at every question.
   */
  bool keepsPace(SequenceView map, int first, int count);
  /// Whether a question about map frames [first, first + count) reads the rows (costs, which computes
  /// those it lacks) rather than searching: at most count / kMissingRowsShare of them lack a row, or
  /// the questions keep pace (keepsPace).
  bool readsRows(SequenceView map, int first, int count);
  /**
   * Records a question about map frames [first, first + count) that was answered without the rows,
   * so that the next question can tell whether it keeps pace. Computes no row: a row kept for a
   * question that comes too late to read it would cost a pass over the map for nothing.
   */
  void noteAsked(SequenceView map, int first, int count);

  /// Forgets every row: the map was emptied or replaced.
  void clear();
  /// Bytes the rows hold (as of the last query: read without waiting for a running one).
  std::size_t memoryBytes() const { return bytes_.load(); }
  /// Frames that have a row.
  int rowCount() const;

 private:
  struct Row {
    int final_end = 0;              ///< Cells [0, final_end) are final.
    float first_difference = 0.0F;  ///< At column 0: every piece of the row is enhanced relative to it.
    std::vector<float> values;      ///< One a map frame; past final_end, scratch.
  };

  /// Cells of a map of `frames` frames that no query's reference end can clip.
  int finalEnd(int frames) const;
  /// Throws std::invalid_argument unless frames [first, first + count) and `columns` lie in `map`.
  void requireInside(SequenceView map, int first, int count, int columns) const;
  /// Drops rows of frames the map no longer holds, or older than the test frames and the newest
  /// kept_rows_; the caller holds mutex_.
  void forgetStaleLocked(SequenceView map, int first, int count);
  /// Checks the frames (requireInside), takes mutex_ and drops stale rows: what every question about
  /// the rows does first.
  std::unique_lock<std::mutex> lockFresh(SequenceView map, int first, int count);
  /// missingRows and keepsPace once stale rows are dropped; the caller holds mutex_.
  int missingRowsLocked(int first, int count) const;
  bool keepsPaceLocked(int first, int count) const;
  /// costs() once the rows are fresh; the caller holds mutex_. May leave rows part-extended when it throws.
  long long costsLocked(SequenceView map, int first, int count, int columns, const SequenceRows& rows,
                        const std::vector<double>& velocities, AnchorCosts& costs);
  /// Sets bytes_; the caller holds mutex_.
  void countBytesLocked();
  /// Extends `rows` (map frame, row) to finalEnd(map.count); returns the comparisons made.
  long long extend(SequenceView map, const std::vector<std::pair<int, Row*>>& rows) const;

  int contrast_window_;
  int max_rows_;

  mutable std::mutex mutex_;
  std::map<int, Row> rows_;  ///< By map frame.
  int kept_rows_ = 0;        ///< The longest test sequence asked lately, at most max_rows_.
  int kept_since_ = 0;       ///< The map's size when it was asked.
  int asked_newest_ = -1;    ///< The newest test frame of the last question noteAsked recorded.
  int asked_map_size_ = 0;   ///< The map's size then: a smaller map is another map.
  std::atomic<std::size_t> bytes_{0};
};

}  // namespace mrs_vpr
