#pragma once

#include <vector>

#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/match.hpp"
#include "mrs_vpr/mrs/compact_cells.hpp"
#include "mrs_vpr/mrs/level_trace.hpp"
#include "mrs_vpr/parameters.hpp"
#include "mrs_vpr/trajectory_search.hpp"

namespace mrs_vpr {

/// Hypotheses closer than this (in cells of the coarsest level, of stride 2^levels) would settle on
/// the same end.
int hypothesisSeparation(const SequenceParams& sequence, const MrsParams& mrs, int levels);

/// The rival of the answer on the coarsest level is another place: an end outside the answer's
/// basin, which on pooled cells is wider than match_exclusion (the hypotheses' separation). At full
/// resolution it is match_exclusion, as for the brute force.
int rivalExclusion(const SequenceParams& sequence, const MrsParams& mrs, int levels);

/**
 * One query of MRS-VPR (Algorithm 1 of the paper) with `levels` levels coarser than the frames:
 * every end of the coarsest level scored densely on compact cells, the paper's particle loop on that
 * table, then mrs.hypotheses of its distinct minima settled level by level down to the frames. The
 * answer is the best end at full resolution, its confidence read on the coarsest table, and
 * acceptance applied; the caller places it (SequenceMatcher::placeAnswer). Each level is recorded
 * into `trace` when it is not null. `levels` 0 is the brute force's own dense search. Throws
 * QueryStopped when `stop` asks to while the coarsest level is scored, which is most of a long query.
 */
Match coarseToFineSearch(SequenceView reference, SequenceView query, const SequenceRows& rows, int levels,
                         const SequenceParams& sequence, const MrsParams& mrs, const CompactCells& compact,
                         std::vector<MrsLevelTrace>* trace, const QueryStop* stop = nullptr,
                         const PlaceLinks* links = nullptr);

}  // namespace mrs_vpr
