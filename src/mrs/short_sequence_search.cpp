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
#include "mrs_vpr/mrs/sampling_level.hpp"
#include "mrs_vpr/mrs/tiled_end_costs.hpp"
#include "mrs_vpr/mrs_matcher.hpp"
#include "mrs_vpr/trajectory_search.hpp"

namespace mrs_vpr {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

/// Every few of the ends costSpread reads in a table of `columns` ends, about kSpreadEnds of them.
int spreadStep(int columns) {
  const int brute_step = std::max<int>(1, columns / kSpreadSamples);
  const int brute_samples = (columns + brute_step - 1) / brute_step;
  return brute_step * std::max(1, brute_samples / kSpreadEnds);
}

/// A stretch of ends whose full costs are wanted.
struct EndRange {
  int begin;
  int end;
};

/// Map-sized tables of one query, kept by the thread that queries (the node's service or timer
/// thread) so that the next query reuses them instead of faulting in fresh pages.
struct QueryTables {
  AnchorCosts first;
  std::vector<float> cost;
  std::vector<float> velocity;
  std::vector<char> known;
};

/// The first pass into `costs`: costsByAnchor of the enhanced differences between the query's cells
/// and the map's cells of `level` (its grid of cells ending at every stride-th frame), a tile at a
/// time. The map's kept cells are used where it has them (complete cells only).
void firstPass(SequenceView reference, SequenceView query_cells, const SamplingLevel& level,
               const std::vector<double>& speeds, int contrast_window, const CompactCells& compact,
               long long& comparisons, AnchorCosts& costs) {
  const SequenceView kept = reference.coarseCells(level.stride, compact.geometry());
  std::atomic<long long> counted{0};
  const auto tile = [&](int begin, int end, cv::Mat& raw) {
    const int known_end = std::clamp(std::min(kept.count, level.grid_size), begin, end);
    if (known_end > begin) {
      cv::Mat columns = raw.colRange(0, known_end - begin);
      computeDifferenceMatrix(query_cells, kept.slice(begin, known_end), columns);
    }
    if (known_end < end) {
      const DescriptorSequence cells =
          compact.cells(reference, known_end * level.stride, level.stride, end - known_end);
      cv::Mat columns = raw.colRange(known_end - begin, end - begin);
      computeDifferenceMatrix(query_cells, cells.view(), columns);
    }
    counted.fetch_add(static_cast<long long>(raw.total()), std::memory_order_relaxed);
  };
  tiledCostsByAnchor(level.grid_size, level.sequenceRows(), speeds, contrast_window, tile, costs);
  comparisons = counted.load();
}

/// Sorted, merged ranges of ends within `radius` of each of `centres`, clipped to the table.
std::vector<EndRange> windowsAround(const std::vector<int>& centres, int radius, int columns) {
  std::vector<EndRange> ranges;
  for (int centre : centres) ranges.push_back({std::max(0, centre - radius), std::min(columns, centre + radius + 1)});
  std::sort(ranges.begin(), ranges.end(), [](const EndRange& a, const EndRange& b) { return a.begin < b.begin; });
  std::vector<EndRange> merged;
  for (const EndRange& range : ranges) {
    if (!merged.empty() && range.begin <= merged.back().end) {
      merged.back().end = std::max(merged.back().end, range.end);
    } else {
      merged.push_back(range);
    }
  }
  return merged;
}

/// Ends [begin, end) where a trajectory of some velocity fits in a map of `columns` frames, as
/// costsByAnchor fits them.
EndRange fittingEnds(const SequenceRows& rows, const std::vector<double>& speeds, int columns) {
  EndRange range{columns, 0};
  for (double speed : speeds) {
    const int back = static_cast<int>(std::lround(speed * (rows.first - rows.anchor)));
    const int ahead = static_cast<int>(std::lround(speed * (rows.last - rows.anchor)));
    if (columns - ahead <= -back) continue;
    range.begin = std::min(range.begin, -back);
    range.end = std::max(range.end, columns - ahead);
  }
  if (range.begin >= range.end) return {0, 0};
  return range;
}

/**
 * costSpread of a sample of the brute force's ends, raised by kSpreadStandardErrors standard errors
 * of a MAD of that many values (1.166 / sqrt(n) of it, for a Gaussian): with a pooled first pass the
 * sample is the only estimate of the brute force's spread, and one too small would lift a query
 * just below the acceptance threshold above it (measured on real frames: winter played backwards,
 * 6 of 843 accepted with the bare sample, none by the brute force).
 */
float sampleSpreadBound(const std::vector<float>& samples) {
  const auto finite = std::count_if(samples.begin(), samples.end(), [](float value) { return std::isfinite(value); });
  if (finite < 3) return 0.0F;
  const double error = 1.166 / std::sqrt(static_cast<double>(finite));
  return static_cast<float>(costSpread(samples) * (1.0 + kSpreadStandardErrors * error));
}

}  // namespace

bool shortSearchPays(int query_length, int reference_count, const SequenceParams& sequence, int hypotheses) {
  if (query_length < 2 || reference_count < query_length) return false;
  const SequenceRows rows = wholeSequenceRows(query_length, sequence.alignment);
  const ChosenEndCosts chosen(SequenceView{}, SequenceView{}, rows, velocities(sequence), sequence.contrast_window);
  // A band of 2 * radius + 1 neighbouring ends costs that many more cells a row than one end.
  const int radius = sequence.match_exclusion + firstPassStride(query_length) - 1;
  const long long band = 2LL * radius * query_length + chosen.comparisonsPerEnd();
  const long long samples = reference_count / spreadStep(reference_count) + 1;
  const long long full = hypotheses * band + samples * chosen.comparisonsPerEnd();
  return kShortSearchGain * full <= static_cast<long long>(query_length) * reference_count;
}

int firstPassStride(int query_length) {
  int stride = 1;
  while (stride < kMaxFirstPassStride && (query_length - 1) / (2 * stride) + 1 >= kMinFirstPassRows) {
    stride *= 2;
  }
  return stride;
}

Match searchShortSequence(SequenceView reference, SequenceView query, const SequenceParams& sequence,
                          const CompactCells& compact, int hypotheses, MrsLevelTrace* trace) {
  compact.requireDescriptorsOf(reference);
  const int columns = reference.count;
  const SequenceRows rows = wholeSequenceRows(query.count, sequence.alignment);
  const std::vector<double> speeds = velocities(sequence);
  Match match;

  // The first pass's level: pooled cells of `stride` frames, its ends J * stride.
  const int stride = firstPassStride(query.count);
  const SamplingLevel level = SamplingLevel::make(stride, rows, columns, speeds.front());
  if (level.empty()) return match;  // No trajectory fits in the reference.
  const DescriptorSequence query_cells =
      compact.cells(query, rows.anchor + level.k_min * stride, stride, level.rows());
  thread_local QueryTables tables;
  long long cell_comparisons = 0;
  const AnchorCosts& first = tables.first;
  firstPass(reference, query_cells.view(), level, speeds, sequence.contrast_window, compact, cell_comparisons,
            tables.first);
  // Minima closer than match_exclusion would settle on the same end.
  const int separation = std::max(1, sequence.match_exclusion / stride);
  std::vector<int> minima = distinctMinima(first.cost, separation, hypotheses);
  for (int& minimum : minima) minimum = std::min(columns - 1, minimum * stride);
  if (trace != nullptr) {
    trace->stride = stride;
    trace->candidates = minima;
    const std::vector<int> table_minima = distinctMinima(first.cost, separation, MrsLevelTrace::kTracedMinima);
    for (int minimum : table_minima) trace->table_minima.push_back(std::min(columns - 1, minimum * stride));
    if (!table_minima.empty()) {
      trace->table_confidence = scoreAround(first.cost, table_minima.front(), separation).confidence;
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
  const auto computeRanges = [&](const std::vector<EndRange>& ranges) {
    std::vector<long long> counts(ranges.size(), 0);
    cv::parallel_for_(cv::Range(0, static_cast<int>(ranges.size())), [&](const cv::Range& part) {
      for (int i = part.start; i < part.end; ++i) {
        const EndRange& range = ranges[static_cast<std::size_t>(i)];
        counts[static_cast<std::size_t>(i)] = chosen.compute(range.begin, range.end, cost.data() + range.begin,
                                                             velocity.data() + range.begin);
      }
    });
    for (std::size_t i = 0; i < ranges.size(); ++i) {
      full_comparisons += counts[i];
      std::fill(known.begin() + ranges[i].begin, known.begin() + ranges[i].end, 1);
    }
  };
  computeRanges(windowsAround(minima, sequence.match_exclusion + stride - 1, columns));
  const auto lowest = std::min_element(cost.begin(), cost.end());  // The first of equals, as the brute force.
  if (!std::isfinite(*lowest)) return match;
  const int winner = static_cast<int>(lowest - cost.begin());

  // The rival may lie on the answer's own slope, just outside its exclusion window: make sure every
  // end there is known. Then the spread's sample.
  std::vector<EndRange> missing;
  for (const EndRange& range : windowsAround({winner}, sequence.match_exclusion, columns)) {
    for (int end = range.begin; end < range.end; ++end) {
      if (!known[static_cast<std::size_t>(end)]) missing.push_back({end, end + 1});
    }
  }
  const EndRange fitting = fittingEnds(rows, speeds, columns);
  std::vector<int> sampled;
  for (int end = 0; end < columns; end += spreadStep(columns)) {
    if (end < fitting.begin || end >= fitting.end) continue;  // No trajectory: costSpread skips it.
    sampled.push_back(end);
    if (!known[static_cast<std::size_t>(end)]) missing.push_back({end, end + 1});
  }
  computeRanges(missing);
  std::vector<float> samples;
  samples.reserve(sampled.size());
  for (int end : sampled) samples.push_back(cost[static_cast<std::size_t>(end)]);

  const int half = sequence.match_exclusion / 2;
  float runner_up = kInfinity;
  for (int end = 0; end < columns; ++end) {
    if (std::abs(end - winner) > half) runner_up = std::min(runner_up, cost[static_cast<std::size_t>(end)]);
  }
  // The brute force's rivals: ends where a trajectory fits, outside the answer's window.
  const int rivals = (fitting.end - fitting.begin) -
                     (std::min(fitting.end, winner + half + 1) - std::max(fitting.begin, winner - half));

  const float best = cost[static_cast<std::size_t>(winner)];
  match.reference_index = winner;
  match.sequence_difference = best;
  match.velocity = velocity[static_cast<std::size_t>(winner)];
  match.score = (std::isfinite(runner_up) && runner_up > 0.0F) ? std::clamp(best / runner_up, 0.0F, 1.0F) : 1.0F;
  match.rivals = rivals;
  // At full resolution the first pass's table is a second estimate of the spread: the larger keeps
  // the confidence from exceeding what either supports. Pooled cells are smoother than frames, so
  // a coarser table's spread is not the brute force's: there the sample alone gives it.
  const float spread =
      stride == 1 ? std::max(costSpread(first.cost), costSpread(samples)) : sampleSpreadBound(samples);
  match.confidence = distinctiveness(best, runner_up, spread, rivals);
  match.comparisons += full_comparisons;
  return match;
}

}  // namespace mrs_vpr
