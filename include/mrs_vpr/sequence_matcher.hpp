#pragma once

#include <memory>
#include <string>
#include <vector>

#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/match.hpp"
#include "mrs_vpr/parameters.hpp"
#include "mrs_vpr/place_links.hpp"
#include "mrs_vpr/query_stop.hpp"
#include "mrs_vpr/trajectory_search.hpp"

namespace mrs_vpr {

/// A method that finds where a test sequence lies in a reference sequence.
class SequenceMatcher {
 public:
  virtual ~SequenceMatcher() = default;

  /**
   * Global localisation: the whole `query` view is the test sequence (oldest first). Returns the
   * reference frame matched to the query's newest frame (frame count / 2 when the alignment is
   * centred). Throws std::invalid_argument when the query is shorter than 2 frames, longer than the
   * reference, or descriptor sizes differ.
   */
  virtual Match match(SequenceView reference, SequenceView query) const = 0;

  /**
   * Per-frame protocol: for every query frame i, the test sequence is the `sequence_length` frames
   * ending at i (centred on i when so aligned). Frames without a full sequence get reference_index -1.
   */
  virtual std::vector<Match> matchEveryFrame(SequenceView reference, SequenceView query) const;

  virtual std::string name() const = 0;

  /// Queries of this matcher that can take long (the brute force over a large map) stop with
  /// QueryStopped once `stop` (which outlives the matcher) asks to; null: never.
  void stopWith(const QueryStop* stop) { stop_ = stop; }
  /// Places that `links` (which outlives the matcher) joins across visits of the reference are no
  /// rivals of each other in the confidence of match() and matchEveryFrame() (PlaceLinks); null: every
  /// other place is a rival.
  void linkPlacesWith(const PlaceLinks* links) { links_ = links; }

 protected:
  explicit SequenceMatcher(const SequenceParams& sequence);
  /// Throws std::invalid_argument with a clear message when the inputs cannot be matched.
  static void checkInputs(SequenceView reference, SequenceView query);
  /// Moves the answer of the straight search to the end of the best flexible path near its trajectory
  /// (sequence/alignment_slack, flexible_alignment.hpp); its confidence stays.
  void placeAnswer(Match& match, SequenceView reference, SequenceView query, const SequenceRows& rows) const;

  SequenceParams sequence_;
  const QueryStop* stop_ = nullptr;
  const PlaceLinks* links_ = nullptr;
};

/// "seqslam" (brute force) or "mrs"; throws std::invalid_argument for any other name or bad parameters.
std::unique_ptr<SequenceMatcher> makeMatcher(const std::string& method, const Parameters& params);

}  // namespace mrs_vpr
