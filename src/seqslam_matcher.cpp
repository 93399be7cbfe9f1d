#include "mrs_vpr/seqslam_matcher.hpp"

#include <algorithm>
#include <cstdint>
#include <string>

#include "mrs_vpr/acceptance.hpp"
#include "mrs_vpr/contrast_enhancement.hpp"
#include "mrs_vpr/difference_matrix.hpp"
#include "mrs_vpr/memory_budget.hpp"
#include "mrs_vpr/query_buffer.hpp"
#include "mrs_vpr/trajectory_search.hpp"

namespace mrs_vpr {

SeqSlamMatcher::SeqSlamMatcher(const SequenceParams& params) : SequenceMatcher(params) {}

Match SeqSlamMatcher::match(SequenceView reference, SequenceView query) const {
  checkInputs(reference, query);
  // Kept by the querying thread (the node's service or timer thread) for its next query. One matrix,
  // enhanced in place: a 1000-frame question on 200k frames needs 0.8 GB, not 1.6.
  thread_local QueryBuffer buffer;
  const std::uint64_t bytes = static_cast<std::uint64_t>(query.count) * static_cast<std::uint64_t>(reference.count) *
                              sizeof(float);
  if (bytes > buffer.capacityBytes()) {
    requireAvailableMemory(bytes,
                           "the difference matrix of a seqslam question about " + std::to_string(query.count) +
                               " frames of a map of " + std::to_string(reference.count),
                           "ask about fewer frames, or use mrs");
  }
  cv::Mat differences = buffer.matrix(query.count, reference.count);
  const QueryBuffer::ReleaseAtExit release(buffer);  // also when the query stops or fails
  computeDifferenceMatrix(query, reference, differences, stop_);
  enhanceContrastInPlace(differences, sequence_.contrast_window, stop_);
  const SequenceRows rows = wholeSequenceRows(query.count, sequence_.alignment);
  Match match = searchTrajectories(differences, rows, sequence_, stop_, links_);
  placeAnswer(match, reference, query, rows);
  applyAcceptance(match, sequence_);
  return match;
}

std::vector<Match> SeqSlamMatcher::matchEveryFrame(SequenceView reference, SequenceView query) const {
  checkInputs(reference, query.slice(0, std::min(query.count, sequence_.sequence_length)));
  requireAvailableMemory(static_cast<std::uint64_t>(query.count) * static_cast<std::uint64_t>(reference.count) *
                             sizeof(float),
                         "the difference matrix of every frame of " + std::to_string(query.count) +
                             " query frames against a map of " + std::to_string(reference.count),
                         "split the query frames into parts and run each");
  // Contrast enhancement works per query frame, so one matrix serves every test sequence.
  cv::Mat enhanced = computeDifferenceMatrix(query, reference);
  enhanceContrastInPlace(enhanced, sequence_.contrast_window);
  std::vector<Match> matches(query.count);
  cv::parallel_for_(cv::Range(0, query.count), [&](const cv::Range& range) {
    for (int frame = range.start; frame < range.end; ++frame) {
      const SequenceRows rows = sequenceRowsFor(frame, sequence_);
      if (rows.first < 0 || rows.last >= query.count) continue;
      matches[frame] = searchTrajectories(enhanced, rows, sequence_, nullptr, links_);
      placeAnswer(matches[frame], reference, query, rows);
      matches[frame].comparisons = static_cast<long long>(reference.count);  // One new row per frame.
      applyAcceptance(matches[frame], sequence_);
    }
  });
  return matches;
}

}  // namespace mrs_vpr
