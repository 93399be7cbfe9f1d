#pragma once

#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/match.hpp"
#include "mrs_vpr/mrs/compact_cells.hpp"
#include "mrs_vpr/parameters.hpp"
#include "mrs_vpr/place_links.hpp"

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
 *    rival the lowest of them outside the answer's own place (ownPlaceEnds: its exclusion window, and
 *    with `links` its place on other visits).
 *
 * The first pass only chooses which ends the full descriptors examine. When the brute force's
 * answer and rival lie within match_exclusion of those minima, both are the brute force's own. The
 * confidence's spread is the larger of two estimates of the brute force's costSpread: the first
 * pass's table (every end; its costs are means of the same contrast-enhanced z-scores along the same
 * trajectories), and the full costs of every kSpreadThinning-th end of the brute force's own sample.
 * On real frames (100k-frame map, N = 10 to 100) either lay within about 10% of the brute force's,
 * the first pass's mostly below it (a higher confidence): the larger keeps the confidence from
 * exceeding what either supports. Rivals are counted exactly (the first pass's table has a trajectory
 * at the same ends).
 */
Match searchShortSequence(SequenceView reference, SequenceView query, const SequenceParams& sequence,
                          const CompactCells& compact, int hypotheses, MrsLevelTrace* trace = nullptr,
                          const PlaceLinks* links = nullptr);

/// Whether the full-descriptor work of searchShortSequence (the hypotheses' bands of ends) is at most
/// 1 / kShortSearchGain of the brute force's comparisons for this query and map.
bool shortSearchPays(int query_length, int reference_count, const SequenceParams& sequence, int hypotheses);

/// The first pass costs about as much as the brute force's contrast enhancement and sums, which it
/// repeats; the full-descriptor work must stay well below the comparisons it saves.
constexpr int kShortSearchGain = 8;

/// The spread's full-descriptor sample: every this-many-th end of costSpread's (about 128 ends).
constexpr int kSpreadThinning = 32;

/// Distinct minima of the first pass scored on the full descriptors. On real frames the brute force's
/// answer and rival lie among them (mrs_vpr_map_scale_benchmark's `same` column); each costs a band
/// of 2 * match_exclusion + 1 ends.
constexpr int kShortSearchHypotheses = 32;

}  // namespace mrs_vpr
