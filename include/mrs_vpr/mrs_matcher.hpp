#pragma once

#include <memory>
#include <vector>

#include "mrs_vpr/mrs/compact_cells.hpp"
#include "mrs_vpr/mrs/level_trace.hpp"
#include "mrs_vpr/mrs/recent_rows.hpp"
#include "mrs_vpr/sequence_matcher.hpp"

namespace mrs_vpr {

/// MRS-VPR: coarse-to-fine particle search over temporally subsampled sequences (Yin et al.).
class MrsMatcher : public SequenceMatcher {
 public:
  /// `descriptor` gives the front end of the descriptors matched, whose compact cells the coarse
  /// levels compare (mrs/compact_cells.hpp).
  MrsMatcher(const SequenceParams& sequence, const MrsParams& mrs, const DescriptorParams& descriptor = {});

  Match match(SequenceView reference, SequenceView query) const override;
  /// The same search, recording each level, coarsest first, into `trace` (when not null).
  Match match(SequenceView reference, SequenceView query, std::vector<MrsLevelTrace>* trace) const;
  /**
   * match() of a test sequence of the map's own frames [first, first + count) against its frames
   * [0, reference_count), as matchRecent asks; `map` is the whole map. A sequence with no coarser
   * level reads and extends the rows `recent` keeps between queries (mrs/recent_rows.hpp): every end
   * is scored as the brute force scores it, for the cost of the trajectory sums and of the rows of
   * frames no earlier query included. When more than a share of the frames lack a row and the
   * questions do not keep pace (RecentRows::readsRows: the first questions, or questions far apart),
   * the search answers as match() does and only notes the question (RecentRows::noteAsked): no row
   * is computed for a question that would come too late to read it.
   */
  Match matchMapFrames(SequenceView map, int reference_count, int first, int count, RecentRows& recent,
                       std::vector<MrsLevelTrace>* trace = nullptr) const;
  /// The search for short sequences on large maps (mrs/short_sequence_search.hpp: a first pass on
  /// compact cells at every end, the full descriptors at its distinct minima), placed and accepted as
  /// match() does, on any map: match() takes it only where it pays (shortSearchPays). Records its one
  /// level into `trace` when not null.
  Match matchByFirstPass(SequenceView reference, SequenceView query, std::vector<MrsLevelTrace>* trace) const;
  /// Per-frame protocol; with no coarser level for sequence_length frames, the brute force's shared
  /// difference matrix gives the same answers once for all frames.
  std::vector<Match> matchEveryFrame(SequenceView reference, SequenceView query) const override;
  std::string name() const override { return "mrs"; }

  /// Levels actually used for a test sequence of `query_length` frames in a reference of
  /// `reference_count`: l_max, capped so that the coarsest level keeps min_coarse_frames frames of
  /// the sequence and kMinRivalEnds ends outside the answer's window, on which its confidence rests.
  int levelsFor(int query_length, int reference_count) const;

 private:
  /// matchByFirstPass() once the inputs are checked.
  Match firstPass(SequenceView reference, SequenceView query, std::vector<MrsLevelTrace>* trace) const;

  MrsParams mrs_;
  std::shared_ptr<const CompactCells> compact_;
};

}  // namespace mrs_vpr
