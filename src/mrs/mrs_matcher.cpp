#include "mrs_vpr/mrs_matcher.hpp"

#include <utility>
#include <vector>

#include "mrs_vpr/acceptance.hpp"
#include "mrs_vpr/mrs/coarse_to_fine_search.hpp"
#include "mrs_vpr/mrs/sampling_level.hpp"
#include "mrs_vpr/mrs/short_sequence_search.hpp"
#include "mrs_vpr/seqslam_matcher.hpp"
#include "mrs_vpr/trajectory_search.hpp"

namespace mrs_vpr {

MrsMatcher::MrsMatcher(const SequenceParams& sequence, const MrsParams& mrs, const DescriptorParams& descriptor)
    : SequenceMatcher(sequence), mrs_(mrs), compact_(makeCompactCells(descriptor)) {
  mrs_.validate();
}

int MrsMatcher::levelsFor(int query_length, int reference_count) const {
  const SequenceRows rows = wholeSequenceRows(query_length, sequence_.alignment);
  const double slowest = velocities(sequence_).front();
  int levels = mrs_.levels;
  for (; levels > 0; --levels) {
    // The paper's l_max = 4 failed with ~19 coarse frames: never let the coarsest level get too short.
    if ((query_length - 1) / (1 << levels) + 1 < mrs_.min_coarse_frames) continue;
    // The answer's confidence is read on the coarsest level's table of ends, so that table must hold
    // enough rivals; a small map is searched at a finer stride instead.
    const SamplingLevel coarsest = SamplingLevel::make(1 << levels, rows, reference_count, slowest);
    const int window = 2 * (rivalExclusion(sequence_, mrs_, levels) / 2) + 1;
    if (coarsest.highest_end - coarsest.lowest_end + 1 - window >= kMinRivalEnds) break;
  }
  return levels;
}

Match MrsMatcher::match(SequenceView reference, SequenceView query) const { return match(reference, query, nullptr); }

std::vector<Match> MrsMatcher::matchEveryFrame(SequenceView reference, SequenceView query) const {
  // Without a coarser level MRS scores every end at full resolution, as the brute force does; the
  // brute force's per-frame path computes the difference matrix once for all frames.
  if (levelsFor(sequence_.sequence_length, reference.count) == 0) {
    SeqSlamMatcher brute_force(sequence_);
    brute_force.linkPlacesWith(links_);
    return brute_force.matchEveryFrame(reference, query);
  }
  return SequenceMatcher::matchEveryFrame(reference, query);
}

Match MrsMatcher::match(SequenceView reference, SequenceView query, std::vector<MrsLevelTrace>* trace) const {
  checkInputs(reference, query);
  const int levels = levelsFor(query.count, reference.count);
  if (levels > 0) compact_->requireDescriptorsOf(reference);
  if (levels == 0 && shortSearchPays(query.count, reference.count, sequence_, kShortSearchHypotheses) &&
      reference.descriptor_size == compact_->descriptorSize()) {
    return firstPass(reference, query, trace);
  }
  const SequenceRows rows = wholeSequenceRows(query.count, sequence_.alignment);
  Match match =
      coarseToFineSearch(reference, query, rows, levels, sequence_, mrs_, *compact_, trace, stop_, links_);
  placeAnswer(match, reference, query, rows);  // As the brute force places its answer.
  return match;
}

Match MrsMatcher::matchByFirstPass(SequenceView reference, SequenceView query,
                                   std::vector<MrsLevelTrace>* trace) const {
  checkInputs(reference, query);
  return firstPass(reference, query, trace);
}

Match MrsMatcher::firstPass(SequenceView reference, SequenceView query, std::vector<MrsLevelTrace>* trace) const {
  MrsLevelTrace level;
  Match match = searchShortSequence(reference, query, sequence_, *compact_, kShortSearchHypotheses,
                                    trace != nullptr ? &level : nullptr, links_);
  if (trace != nullptr) trace->push_back(std::move(level));
  placeAnswer(match, reference, query, wholeSequenceRows(query.count, sequence_.alignment));
  applyAcceptance(match, sequence_);
  return match;
}

Match MrsMatcher::matchMapFrames(SequenceView map, int reference_count, int first, int count, RecentRows& recent,
                                 std::vector<MrsLevelTrace>* trace) const {
  const SequenceView reference = map.slice(0, reference_count);
  const SequenceView query = map.slice(first, first + count);
  checkInputs(reference, query);
  if (levelsFor(count, reference_count) > 0 || !recent.covers(count)) return match(reference, query, trace);
  if (!recent.readsRows(map, first, count)) {
    // Rows for more than a quarter of the frames would cost a good part of the brute force at every
    // question that comes too late for the rows to keep up: the search answers, and the question is
    // noted, so that the next one computes the rows if it keeps pace.
    recent.noteAsked(map, first, count);
    return match(reference, query, trace);
  }
  const SequenceRows rows = wholeSequenceRows(count, sequence_.alignment);
  thread_local AnchorCosts costs;  // Map-sized: kept by the querying thread for its next query.
  const long long comparisons =
      recent.costs(map, first, count, reference_count, rows, velocities(sequence_), costs);
  Match result = scoreAnchorCosts(costs, sequence_.match_exclusion, links_);  // As the brute force scores its table.
  result.comparisons = comparisons;
  if (trace != nullptr) {
    MrsLevelTrace level;
    level.table_minima = distinctMinima(costs.cost, sequence_.match_exclusion, MrsLevelTrace::kTracedMinima);
    level.candidates = level.table_minima;
    level.table_confidence = result.confidence;
    trace->push_back(std::move(level));
  }
  placeAnswer(result, reference, query, rows);
  applyAcceptance(result, sequence_);
  return result;
}

}  // namespace mrs_vpr
