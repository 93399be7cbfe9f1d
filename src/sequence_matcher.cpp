#include "mrs_vpr/sequence_matcher.hpp"

#include <stdexcept>
#include <string>

#include "mrs_vpr/flexible_alignment.hpp"
#include "mrs_vpr/mrs_matcher.hpp"
#include "mrs_vpr/seqslam_matcher.hpp"
#include "mrs_vpr/trajectory_search.hpp"

namespace mrs_vpr {

SequenceMatcher::SequenceMatcher(const SequenceParams& sequence) : sequence_(sequence) {
  sequence_.validate();
}

void SequenceMatcher::checkInputs(SequenceView reference, SequenceView query) {
  if (query.descriptor_size != reference.descriptor_size) {
    throw std::invalid_argument("query descriptors have " + std::to_string(query.descriptor_size) +
                                " bytes but reference descriptors have " +
                                std::to_string(reference.descriptor_size));
  }
  if (query.count < kMinSequenceFrames) {
    throw std::invalid_argument("a test sequence needs at least " + std::to_string(kMinSequenceFrames) +
                                " frames, got " + std::to_string(query.count));
  }
  if (query.count > reference.count) {
    throw std::invalid_argument("test sequence of " + std::to_string(query.count) +
                                " frames is longer than the reference of " + std::to_string(reference.count) +
                                " frames");
  }
}

void SequenceMatcher::placeAnswer(Match& match, SequenceView reference, SequenceView query,
                                  const SequenceRows& rows) const {
  match.reference_index = realignEnd(reference, query, rows, match.reference_index, match.velocity,
                                     sequence_.alignment_slack, sequence_.contrast_window);
}

std::vector<Match> SequenceMatcher::matchEveryFrame(SequenceView reference, SequenceView query) const {
  std::vector<Match> matches(query.count);
  for (int frame = 0; frame < query.count; ++frame) {
    const SequenceRows rows = sequenceRowsFor(frame, sequence_);
    if (rows.first < 0 || rows.last >= query.count) continue;
    matches[frame] = match(reference, query.slice(rows.first, rows.last + 1));
  }
  return matches;
}

std::unique_ptr<SequenceMatcher> makeMatcher(const std::string& method, const Parameters& params) {
  if (method == "seqslam") return std::make_unique<SeqSlamMatcher>(params.sequence);
  if (method == "mrs") return std::make_unique<MrsMatcher>(params.sequence, params.mrs, params.descriptor);
  throw std::invalid_argument("unknown method '" + method + "' (expected 'mrs' or 'seqslam')");
}

}  // namespace mrs_vpr
