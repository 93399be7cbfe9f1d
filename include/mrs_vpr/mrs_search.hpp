#pragma once

#include "mrs_vpr/sequence_matcher.hpp"

namespace mrs_vpr {

/// MRS-VPR: coarse-to-fine particle search over temporally subsampled sequences (Yin et al.).
class MrsSearch : public SequenceMatcher {
 public:
  MrsSearch(const SequenceParams& sequence, const MrsParams& mrs);

  Match match(SequenceView reference, SequenceView query) const override;
  std::string name() const override { return "mrs"; }

  /// Levels actually used for a test sequence of `query_length` frames (l_max capped so that the
  /// coarsest level keeps min_coarse_frames frames).
  int levelsFor(int query_length) const;

 private:
  MrsParams mrs_;
};

}  // namespace mrs_vpr
