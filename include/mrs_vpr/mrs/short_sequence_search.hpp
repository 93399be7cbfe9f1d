#pragma once

#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/match.hpp"
#include "mrs_vpr/mrs/compact_cells.hpp"
#include "mrs_vpr/parameters.hpp"

namespace mrs_vpr {

struct MrsLevelTrace;

/**
 * MRS for a test sequence too short for a coarser level (MrsMatcher::levelsFor gives 0), on a map
 * large enough for it to pay (shortSearchPays). Two levels:
 *
 * 1. A first pass scores every end of the map, as the brute force does (contrast enhancement, every
 *    velocity), but on compact cells (mrs/compact_cells.hpp) pooled over `stride` frames
 *    (firstPassStride; the map keeps them for strides 1, 2, 4 and 8): the query's cells ending at
 *    every stride-th of its frames against the map's cells ending at every stride-th frame, so a
 *    stride of s costs 1 / s^2 of the full-resolution pass.
 * 2. Its `hypotheses` lowest distinct minima, and every end within match_exclusion + stride - 1 of
 *    each (a pooled minimum lies within a cell of the full-resolution one), are scored on the full
 *    descriptors (ChosenEndCosts): the answer is the lowest of those ends, its rival the lowest of
 *    them outside the answer's exclusion window.
 *
 * The first pass only chooses which ends the full descriptors examine. When the brute force's
 * answer and rival lie within match_exclusion of those minima, both are the brute force's own. The
 * confidence's spread estimates the brute force's costSpread from the full costs of kSpreadEnds
 * ends of its own sample; at stride 1 it is the larger of that and the first
 * pass's table (every end; its costs are means of the same contrast-enhanced z-scores along the same
 * trajectories), so that the confidence never exceeds what either supports. Rivals are counted
 * exactly (the ends where a trajectory fits).
 */
Match searchShortSequence(SequenceView reference, SequenceView query, const SequenceParams& sequence,
                          const CompactCells& compact, int hypotheses, MrsLevelTrace* trace = nullptr);

/// Whether the full-descriptor work of searchShortSequence (the hypotheses' bands of ends) is at most
/// 1 / kShortSearchGain of the brute force's comparisons for this query and map.
bool shortSearchPays(int query_length, int reference_count, const SequenceParams& sequence, int hypotheses);

/// The first pass's stride for a test sequence of `query_length` frames: the largest power of two up
/// to kMaxFirstPassStride that leaves the pooled query at least kMinFirstPassRows cells.
int firstPassStride(int query_length);

/// The coarsest cells the map keeps (MrsParams::levels = 3).
constexpr int kMaxFirstPassStride = 8;

/// Pooled query cells the first pass needs to rank the truth among its minima as the full-resolution
/// pass does (real frames, mrs_vpr_real_benchmark --diagnose).
constexpr int kMinFirstPassRows = 12;

/// The first pass costs about as much as the brute force's contrast enhancement and sums, which it
/// repeats; the full-descriptor work must stay well below the comparisons it saves.
constexpr int kShortSearchGain = 8;

/// Ends of the spread's full-descriptor sample, evenly spaced among costSpread's own (at least this
/// many where the map has them).
constexpr int kSpreadEnds = 128;

/// Standard errors of the sample's spread added to it when it is the only estimate (pooled first pass).
constexpr double kSpreadStandardErrors = 2.0;

/// Distinct minima of the first pass scored on the full descriptors. On real frames the brute force's
/// answer and rival lie among them (mrs_vpr_map_scale_benchmark's `same` column); each costs a band
/// of 2 * match_exclusion + 1 ends.
constexpr int kShortSearchHypotheses = 32;

}  // namespace mrs_vpr
