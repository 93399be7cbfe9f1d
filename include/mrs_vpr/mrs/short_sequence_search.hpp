#pragma once

#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/match.hpp"
#include "mrs_vpr/mrs/compact_cells.hpp"
#include "mrs_vpr/parameters.hpp"

namespace mrs_vpr {

struct MrsLevelTrace;

/**
 * MRS for a test sequence too short for a coarser level (MrsMatcher::levelsFor gives 0), on a map
 * large enough for it to pay (shortSearchPays). Two levels, both at full temporal resolution:
 *
 * 1. A first pass scores every end of the map, as the brute force does (contrast enhancement, every
 *    velocity), but on compact cells (mrs/compact_cells.hpp; the map keeps them for its frames).
 * 2. Its `hypotheses` lowest distinct minima, and every end within match_exclusion of each, are
 *    scored on the full descriptors (ChosenEndCosts): the answer is the lowest of those ends, its
 *    rival the lowest of them outside the answer's exclusion window.
 *
 * The first pass only chooses which ends the full descriptors examine. When the brute force's
 * answer and rival lie within match_exclusion of those minima, both are the brute force's own. The
 * confidence's spread is costSpread of the full costs of every kSpreadThinning-th end that
 * costSpread reads in the brute force's table: a subset of its sample, so it differs from the brute
 * force's by the sampling error of the smaller sample (about 3% with 512 ends). Rivals are counted
 * exactly (the first pass's table has a trajectory at the same ends).
 */
Match searchShortSequence(SequenceView reference, SequenceView query, const SequenceParams& sequence,
                          const CompactCells& compact, int hypotheses, MrsLevelTrace* trace = nullptr);

/// Whether the full-descriptor work of searchShortSequence (the hypotheses' windows and the spread's
/// sample) is at most a quarter of the brute force's comparisons for this query and map.
bool shortSearchPays(int query_length, int reference_count, const SequenceParams& sequence, int hypotheses);

/// Distinct minima of the first pass scored on the full descriptors. On real frames the brute force's
/// answer and rival lie among them (mrs_vpr_map_scale_benchmark's `same` column); each costs a band
/// of 2 * match_exclusion + 1 ends.
constexpr int kShortSearchHypotheses = 32;

/// The brute force's spread sample (kSpreadSamples ends) thinned by this factor.
constexpr int kSpreadThinning = 8;

}  // namespace mrs_vpr
