#include "mrs_vpr/mrs/short_sequence_search.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include <opencv2/core/utility.hpp>

#include "mrs_vpr/acceptance.hpp"
#include "mrs_vpr/difference_matrix.hpp"
#include "mrs_vpr/mrs/chosen_end_costs.hpp"
#include "mrs_vpr/mrs/tiled_end_costs.hpp"
#include "mrs_vpr/mrs_matcher.hpp"
#include "mrs_vpr/trajectory_search.hpp"

namespace mrs_vpr {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

/// Every kSpreadThinning-th of the ends costSpread reads in a table of `columns` ends.
int spreadStep(int columns) { return std::max<int>(1, columns / kSpreadSamples) * kSpreadThinning; }

/// Map-sized tables of one query, kept by the thread that queries (the node's service or timer
/// thread) so that the next query reuses them instead of faulting in fresh pages.
struct QueryTables {
  AnchorCosts first;
  std::vector<float> cost;
  std::vector<float> velocity;
  std::vector<char> known;
};

/// The first pass into `costs`: costsByAnchor of the enhanced differences between compact cells of
/// every frame, a tile at a time. The map's kept cells are used where it has them.
void firstPass(SequenceView reference, SequenceView query_cells, const SequenceRows& rows,
               const std::vector<double>& speeds, int contrast_window, const CompactCells& compact,
               long long& comparisons, AnchorCosts& costs) {
  std::atomic<long long> counted{0};
  const auto tile = [&](int begin, int end, cv::Mat& raw) {
    cellDifferences(query_cells, reference, 1, reference.count, compact, begin, end, raw);
    counted.fetch_add(static_cast<long long>(raw.total()), std::memory_order_relaxed);
  };
  tiledCostsByAnchor(reference.count, rows, speeds, contrast_window, tile, costs);
  comparisons = counted.load();
}

/// Sorted, merged ranges of ends within `radius` of each of `centres`, clipped to the table.
std::vector<FrameRange> windowsAround(const std::vector<int>& centres, int radius, int columns) {
  std::vector<FrameRange> ranges;
  for (int centre : centres) ranges.push_back({std::max(0, centre - radius), std::min(columns, centre + radius + 1)});
  return mergedRanges(std::move(ranges));
}

}  // namespace

bool shortSearchPays(int query_length, int reference_count, const SequenceParams& sequence, int hypotheses) {
  if (query_length < 2 || reference_count < query_length) return false;
  const SequenceRows rows = wholeSequenceRows(query_length, sequence.alignment);
  const ChosenEndCosts chosen(SequenceView{}, SequenceView{}, rows, velocities(sequence), sequence.contrast_window);
  // A band of 2 * match_exclusion + 1 neighbouring ends costs that many more cells a row than one end.
  const long long band = 2LL * sequence.match_exclusion * query_length + chosen.comparisonsPerEnd();
  const long long samples = reference_count / spreadStep(reference_count) + 1;
  const long long full = hypotheses * band + samples * chosen.comparisonsPerEnd();
  return kShortSearchGain * full <= static_cast<long long>(query_length) * reference_count;
}

Match searchShortSequence(SequenceView reference, SequenceView query, const SequenceParams& sequence,
                          const CompactCells& compact, int hypotheses, MrsLevelTrace* trace,
                          const PlaceLinks* links) {
  compact.requireDescriptorsOf(reference);
  const int columns = reference.count;
  const SequenceRows rows = wholeSequenceRows(query.count, sequence.alignment);
  const std::vector<double> speeds = velocities(sequence);
  Match match;

  const DescriptorSequence query_cells = compact.cells(query, 0, 1, query.count);
  thread_local QueryTables tables;
  long long cell_comparisons = 0;
  const AnchorCosts& first = tables.first;
  firstPass(reference, query_cells.view(), rows, speeds, sequence.contrast_window, compact, cell_comparisons,
            tables.first);
  const std::vector<int> minima = distinctMinima(first.cost, sequence.match_exclusion, hypotheses);
  if (trace != nullptr) {
    trace->stride = 1;
    trace->candidates = minima;
    trace->table_minima = distinctMinima(first.cost, sequence.match_exclusion, MrsLevelTrace::kTracedMinima);
    if (!trace->table_minima.empty()) {
      trace->table_confidence =
          scoreAround(first.cost, trace->table_minima.front(), sequence.match_exclusion, links).confidence;
    }
  }
  match.comparisons = std::llround(static_cast<double>(cell_comparisons) * compact.cellSize() /
                                   compact.descriptorSize());
  if (minima.empty()) return match;  // No trajectory fits in the reference.

  // Full costs of the ends the first pass chose, and of the spread's sample; infinity = not computed.
  const ChosenEndCosts chosen(reference, query, rows, speeds, sequence.contrast_window);
  std::vector<float>& cost = tables.cost;
  std::vector<float>& velocity = tables.velocity;
  std::vector<char>& known = tables.known;
  cost.assign(static_cast<std::size_t>(columns), kInfinity);
  velocity.assign(static_cast<std::size_t>(columns), 0.0F);
  known.assign(static_cast<std::size_t>(columns), 0);
  long long full_comparisons = 0;
  const auto computeRanges = [&](const std::vector<FrameRange>& ranges) {
    std::vector<long long> counts(ranges.size(), 0);
    cv::parallel_for_(cv::Range(0, static_cast<int>(ranges.size())), [&](const cv::Range& part) {
      for (int i = part.start; i < part.end; ++i) {
        const FrameRange& range = ranges[static_cast<std::size_t>(i)];
        counts[static_cast<std::size_t>(i)] = chosen.compute(range.begin, range.end, cost.data() + range.begin,
                                                             velocity.data() + range.begin);
      }
    });
    for (std::size_t i = 0; i < ranges.size(); ++i) {
      full_comparisons += counts[i];
      std::fill(known.begin() + ranges[i].begin, known.begin() + ranges[i].end, 1);
    }
  };
  computeRanges(windowsAround(minima, sequence.match_exclusion, columns));
  const auto lowest = std::min_element(cost.begin(), cost.end());  // The first of equals, as the brute force.
  if (!std::isfinite(*lowest)) return match;
  const int winner = static_cast<int>(lowest - cost.begin());

  // The rival may lie on the answer's own slope, just outside its exclusion window: make sure every
  // end there is known. Then the spread's sample. An end is queued once (marked known as it is), so
  // that no two threads compute it and it is counted once.
  std::vector<FrameRange> missing;
  const auto queue = [&](int end) {
    if (known[static_cast<std::size_t>(end)]) return;
    known[static_cast<std::size_t>(end)] = 1;
    missing.push_back({end, end + 1});
  };
  for (const FrameRange& range : windowsAround({winner}, sequence.match_exclusion, columns)) {
    for (int end = range.begin; end < range.end; ++end) queue(end);
  }
  std::vector<int> sampled;
  for (int end = 0; end < columns; end += spreadStep(columns)) {
    if (!std::isfinite(first.cost[static_cast<std::size_t>(end)])) continue;  // No trajectory: costSpread skips it.
    sampled.push_back(end);
    queue(end);
  }
  computeRanges(missing);
  std::vector<float> samples;
  samples.reserve(sampled.size());
  for (int end : sampled) samples.push_back(cost[static_cast<std::size_t>(end)]);

  const std::vector<FrameRange> own = ownPlaceEnds(winner, sequence.match_exclusion, columns, links);
  const float runner_up = rivalsOutside(cost, own).lowest;
  const int rivals = rivalsOutside(first.cost, own).finite;

  const float best = cost[static_cast<std::size_t>(winner)];
  match.reference_index = winner;
  match.sequence_difference = best;
  match.velocity = velocity[static_cast<std::size_t>(winner)];
  match.score = (std::isfinite(runner_up) && runner_up > 0.0F) ? std::clamp(best / runner_up, 0.0F, 1.0F) : 1.0F;
  match.rivals = rivals;
  match.rival_places = placesAmong(rivals, 1, sequence.match_exclusion);
  // The larger of the two estimates of the spread: a confidence never above what either supports.
  const float spread = std::max(costSpread(first.cost), costSpread(samples));
  match.confidence = distinctiveness(best, runner_up, spread, rivals);
  match.comparisons += full_comparisons;
  return match;
}

}  // namespace mrs_vpr
