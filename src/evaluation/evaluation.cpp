#include "mrs_vpr/evaluation/evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>

#include "mrs_vpr/acceptance.hpp"
#include "mrs_vpr/median.hpp"
#include "mrs_vpr/trajectory_search.hpp"

namespace mrs_vpr {

namespace {

void checkTolerance(int tolerance) {
  if (tolerance < 0) {
    throw std::invalid_argument("tolerance must be >= 0 frames, got " + std::to_string(tolerance));
  }
}

/// Uniform integer in [0, n) from the generator's raw output. std::uniform_int_distribution is
/// implementation-defined, so it would give other positions with another standard library.
std::uint64_t uniformBelow(std::mt19937_64& generator, std::uint64_t n) {
  // 2^64 mod n: raw values below it would make small results more likely.
  const std::uint64_t reject_below = (0 - n) % n;
  std::uint64_t value = 0;
  do {
    value = generator();
  } while (value < reject_below);
  return value % n;
}

}  // namespace

namespace {

/// Frames from the predicted span (predicted_index .. predicted_last) to `index`; 0 inside it.
int distanceToPrediction(const QueryRecord& record, int index) {
  const int last = std::max(record.predicted_index, record.predicted_last);
  if (index < record.predicted_index) return record.predicted_index - index;
  return index > last ? index - last : 0;
}

}  // namespace

int Keyframes::lastFrameOf(int keyframe) const {
  if (keyframe < 0 || keyframe >= static_cast<int>(frames.size())) {
    throw std::out_of_range("keyframe " + std::to_string(keyframe) + " of " + std::to_string(frames.size()));
  }
  const auto next = static_cast<std::size_t>(keyframe) + 1;
  return (next < frames.size() ? frames[next] : total) - 1;
}

QueryRecord keyframeRecordOf(int query_frame, std::vector<int> truth, const Match& match, const Keyframes& reference,
                             double time_ms) {
  QueryRecord record = queryRecordOf(query_frame, std::move(truth), match, time_ms);
  if (match.reference_index >= 0) {
    record.predicted_index = reference.frames.at(static_cast<std::size_t>(match.reference_index));
    record.predicted_last = reference.lastFrameOf(match.reference_index);
  }
  return record;
}

int absoluteError(const QueryRecord& record) {
  const int nearest = nearestTrueIndex(record);
  if (record.predicted_index < 0 || nearest < 0) return -1;
  return distanceToPrediction(record, nearest);
}

int nearestTrueIndex(const QueryRecord& record) {
  if (record.true_indices.empty()) return -1;
  if (record.predicted_index < 0) return record.true_indices.front();
  int nearest = record.true_indices.front();
  for (int index : record.true_indices) {
    if (distanceToPrediction(record, index) < distanceToPrediction(record, nearest)) nearest = index;
  }
  return nearest;
}

bool isCorrect(const QueryRecord& record, int tolerance) {
  const int error = absoluteError(record);
  return error >= 0 && error <= tolerance;
}

int queriesInMap(const std::vector<QueryRecord>& records) {
  return static_cast<int>(
      std::count_if(records.begin(), records.end(), [](const QueryRecord& r) { return !r.true_indices.empty(); }));
}

double top1Accuracy(const std::vector<QueryRecord>& records, int tolerance) {
  checkTolerance(tolerance);
  const int in_map = queriesInMap(records);
  if (in_map == 0) return std::numeric_limits<double>::quiet_NaN();
  const auto correct = std::count_if(records.begin(), records.end(),
                                     [tolerance](const QueryRecord& r) { return isCorrect(r, tolerance); });
  return static_cast<double>(correct) / in_map;
}

QueryRecord queryRecordOf(int query_index, std::vector<int> truth, const Match& match, double time_ms) {
  QueryRecord record;
  record.query_index = query_index;
  record.true_indices = std::move(truth);
  record.predicted_index = match.reference_index;
  record.predicted_last = match.reference_index;
  record.score = match.score;
  record.confidence = match.confidence;
  record.accepted = match.accepted;
  record.rival_places = match.rival_places;
  record.at_velocity_bound = match.at_velocity_bound;
  record.repeated_view = match.repeated_view;
  record.time_ms = time_ms;
  return record;
}

std::vector<PrPoint> precisionRecallCurve(const std::vector<QueryRecord>& records, int tolerance) {
  checkTolerance(tolerance);
  std::vector<const QueryRecord*> predicted;
  for (const QueryRecord& record : records) {
    if (record.predicted_index < 0) continue;
    // No threshold is equal to NaN: the curve would never pass it (and the ranking would be no order).
    if (std::isnan(record.confidence)) {
      throw std::invalid_argument("the record of query " + std::to_string(record.query_index) +
                                  " has a confidence that is not a number");
    }
    predicted.push_back(&record);
  }
  std::sort(predicted.begin(), predicted.end(),
            [](const QueryRecord* a, const QueryRecord* b) { return a->confidence > b->confidence; });

  std::vector<PrPoint> curve;
  // Over the queries whose place is in the map; NaN when there is none.
  const int queries_in_map = queriesInMap(records);
  const double in_map = queries_in_map > 0 ? queries_in_map : std::numeric_limits<double>::quiet_NaN();
  int accepted = 0;
  int correct = 0;
  // Queries of equal confidence are accepted together: a threshold cannot separate them.
  for (std::size_t i = 0; i < predicted.size();) {
    const float threshold = predicted[i]->confidence;
    for (; i < predicted.size() && predicted[i]->confidence == threshold; ++i) {
      ++accepted;
      if (isCorrect(*predicted[i], tolerance)) ++correct;
    }
    PrPoint point;
    point.threshold = threshold;
    point.precision = static_cast<double>(correct) / accepted;
    point.recall = correct / in_map;
    curve.push_back(point);
  }
  return curve;
}

double averagePrecision(const std::vector<PrPoint>& curve) {
  double area = 0.0;
  double previous_recall = 0.0;
  for (const PrPoint& point : curve) {
    area += (point.recall - previous_recall) * point.precision;
    previous_recall = point.recall;
  }
  return area;
}

double recallAtFullPrecision(const std::vector<PrPoint>& curve) {
  double best = 0.0;
  for (const PrPoint& point : curve) {
    if (point.precision == 1.0) best = std::max(best, point.recall);
  }
  return best;
}

double median(std::vector<double> values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  const std::size_t middle = values.size() / 2;
  const double upper = upperMedian(values);  // Leaves the lower half before `middle`.
  if (values.size() % 2 == 1) return upper;
  const double lower = *std::max_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(middle));
  return 0.5 * (lower + upper);
}

EvaluationSummary summarise(const std::vector<QueryRecord>& records, int tolerance) {
  checkTolerance(tolerance);
  EvaluationSummary summary;
  summary.tolerance = tolerance;
  summary.queries = static_cast<int>(records.size());
  summary.queries_in_map = queriesInMap(records);
  summary.top1 = top1Accuracy(records, tolerance);
  const std::vector<PrPoint> curve = precisionRecallCurve(records, tolerance);
  // A curve of one point ranks nothing (every confidence equal, such as the 0 of a map too small for
  // the acceptance rule): its area would be top-1 times the precision of all answers, a figure of
  // no threshold.
  const bool ranked = summary.queries_in_map > 0 && curve.size() >= 2;
  const double unranked = std::numeric_limits<double>::quiet_NaN();
  summary.pr_auc = ranked ? averagePrecision(curve) : unranked;
  summary.recall_at_100_precision = ranked ? recallAtFullPrecision(curve) : unranked;

  std::vector<double> errors;
  std::vector<double> times;
  double total_ms = 0.0;
  int accepted_correct = 0;
  int largest_wrong_error = -1;  // None yet.
  for (const QueryRecord& record : records) {
    const int error = absoluteError(record);
    if (record.accepted) {
      ++summary.accepted;
      if (isCorrect(record, tolerance)) {
        ++accepted_correct;
      } else if (error >= 0) {
        largest_wrong_error = std::max(largest_wrong_error, error);
      }
    }
    if (error >= 0) errors.push_back(error);
    times.push_back(record.time_ms);
    total_ms += record.time_ms;
  }
  if (!records.empty()) {
    summary.accepted_rate = static_cast<double>(summary.accepted) / static_cast<double>(records.size());
  }
  summary.accepted_recall = summary.queries_in_map > 0 ? static_cast<double>(accepted_correct) / summary.queries_in_map
                                                       : std::numeric_limits<double>::quiet_NaN();
  if (summary.accepted > 0) summary.accepted_precision = static_cast<double>(accepted_correct) / summary.accepted;
  if (largest_wrong_error >= 0) summary.largest_wrong_accepted_error = largest_wrong_error;
  summary.median_abs_error = median(errors);
  summary.median_time_ms = median(times);
  summary.total_time_s = total_ms / 1000.0;
  return summary;
}

std::vector<int> perFrameQueries(int query_frames, const SequenceParams& params) {
  std::vector<int> frames;
  for (int frame = 0; frame < query_frames; ++frame) {
    const SequenceRows rows = sequenceRowsFor(frame, params);
    if (rows.first >= 0 && rows.last < query_frames) frames.push_back(frame);
  }
  return frames;
}

std::vector<TestSequence> globalQueries(int query_frames, int length, int count, std::uint64_t seed,
                                        WindowAlignment alignment) {
  if (length < 1) throw std::invalid_argument("test sequence length must be >= 1, got " + std::to_string(length));
  if (count < 0) throw std::invalid_argument("query count must be >= 0, got " + std::to_string(count));
  if (length > query_frames) {
    throw std::invalid_argument("test sequences of " + std::to_string(length) + " frames do not fit in a query of " +
                                std::to_string(query_frames) + " frames");
  }
  const int positions = query_frames - length + 1;
  std::mt19937_64 generator(seed);
  std::multiset<int> starts;
  if (count <= positions) {
    // Floyd's algorithm: `count` distinct positions with `count` draws, whatever `positions` is.
    for (int j = positions - count; j < positions; ++j) {
      const int candidate = static_cast<int>(uniformBelow(generator, static_cast<std::uint64_t>(j) + 1));
      starts.insert(starts.count(candidate) > 0 ? j : candidate);
    }
  } else {
    for (int start = 0; start < positions; ++start) starts.insert(start);
    for (int i = positions; i < count; ++i) {
      starts.insert(static_cast<int>(uniformBelow(generator, static_cast<std::uint64_t>(positions))));
    }
  }

  // The localised frame sits where sequenceRowsFor puts the anchor relative to the first frame.
  SequenceParams rows_params;
  rows_params.sequence_length = length;
  rows_params.alignment = alignment;
  const int anchor_offset = -sequenceRowsFor(0, rows_params).first;

  std::vector<TestSequence> sequences;
  sequences.reserve(starts.size());
  for (int start : starts) sequences.push_back({start, length, start + anchor_offset});
  return sequences;
}

void checkGroundTruth(const GroundTruth& ground_truth, int query_frames, int reference_frames) {
  for (const auto& [query_index, matches] : ground_truth) {
    const std::string row = "ground truth row of query frame " + std::to_string(query_index);
    if (query_index < 0 || query_index >= query_frames) {
      throw std::invalid_argument(row + ": the query has " + std::to_string(query_frames) + " frames");
    }
    for (int reference_index : matches) {
      if (reference_index < 0 || reference_index >= reference_frames) {
        throw std::invalid_argument(row + " lists reference frame " + std::to_string(reference_index) +
                                    ", but the reference has " + std::to_string(reference_frames) + " frames");
      }
    }
  }
}

std::string repeatedGlobalQueries(int query_frames, int length, int count) {
  const int positions = query_frames - length + 1;
  if (count <= positions) return "";
  return std::to_string(count) + " test sequences, but the query has " + std::to_string(positions) +
         " positions for one: each position once, and " + std::to_string(count - positions) +
         " of them again (the summary counts every test sequence)";
}

bool hasTooFewRivals(const Match& match) { return match.reference_index >= 0 && match.rivals < kMinRivalEnds; }

std::string tooFewRivalsNote(int too_few, int answers, int map_keyframes) {
  if (too_few <= 0) return "";
  return std::to_string(too_few) + " of " + std::to_string(answers) + " answers found fewer than " +
         std::to_string(kMinRivalEnds) + " trajectory ends outside their window in the map of " +
         std::to_string(map_keyframes) + " keyframes: the acceptance rule gives them confidence 0 and accepts none " +
         "of them" +
         (too_few == answers ? "; every confidence is equal, so there is no PR curve (a map of a few hundred "
                               "keyframes or more has one)"
                             : "") +
         " (doc/acceptance.md)";
}

std::optional<std::vector<int>> truthFor(int query_index, const GroundTruth* ground_truth, int reference_frames) {
  if (ground_truth != nullptr) {
    const auto entry = ground_truth->find(query_index);
    if (entry == ground_truth->end()) return std::nullopt;
    return entry->second;
  }
  if (query_index < 0 || query_index >= reference_frames) return std::nullopt;
  return std::vector<int>{query_index};
}

}  // namespace mrs_vpr
