#pragma once

#include "mrs_vpr/sequence_matcher.hpp"

namespace mrs_vpr {

/// OpenSeqSLAM's brute-force sequence matching: full difference matrix, local contrast
/// enhancement, every anchor and velocity.
class SeqSlamMatcher : public SequenceMatcher {
 public:
  explicit SeqSlamMatcher(const SequenceParams& params);

  Match match(SequenceView reference, SequenceView query) const override;
  /// Computes the difference matrix once for all query frames.
  std::vector<Match> matchEveryFrame(SequenceView reference, SequenceView query) const override;
  std::string name() const override { return "seqslam"; }
};

}  // namespace mrs_vpr
