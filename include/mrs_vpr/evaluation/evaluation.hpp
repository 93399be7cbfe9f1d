#pragma once

#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "mrs_vpr/match.hpp"
#include "mrs_vpr/parameters.hpp"

namespace mrs_vpr {

/// The protocols' defaults and limits, as mrs_vpr_eval and Python's evaluate() take them; the global
/// protocol's default seed is MrsParams::seed's.
constexpr int kDefaultTolerance = 2;        ///< [frames]: an answer this near the truth is right.
constexpr int kDefaultGlobalQueries = 200;  ///< Test sequences of the global protocol.
constexpr int kMaxGlobalQueries = 100000;   ///< Each keeps a record: a million of them took 1.7 GB.

/// Ground truth: query frame -> the reference frames that show the same place (possibly several,
/// possibly none). Query frames without an entry are not evaluated.
using GroundTruth = std::map<int, std::vector<int>>;

/// The outcome of one test sequence.
struct QueryRecord {
  int query_index = 0;            ///< Query frame localised (where the test sequence ends when causal).
  std::vector<int> true_indices;  ///< Reference frames that are correct answers (empty: none is).
  int predicted_index = -1;       ///< Reference frame returned; -1 when the method returned none.
  /// The last reference frame the answer stands for: a keyframe stands for the frames after it that
  /// were too similar to become keyframes (keyframeRecordOf); equal to predicted_index otherwise.
  int predicted_last = -1;
  float score = 1.0F;             ///< Best / runner-up, lower is better.
  float confidence = 0.0F;        ///< Distinctiveness, higher is surer; the PR curve sweeps a threshold on it.
  bool accepted = false;          ///< Passed the acceptance rule (Match::accepted).
  int rival_places = 0;           ///< Places the confidence was judged among (Match::rival_places).
  /// The answer's trajectory runs at a velocity bound (Match::at_velocity_bound; confidence 0).
  bool at_velocity_bound = false;
  /// Most of the test sequence's keyframes show one view again (Match::repeated_view; not accepted).
  bool repeated_view = false;
  double time_ms = 0.0;           ///< Time spent on this query.
};

/// The record of the answer `match` to the query localising `query_index`, whose true places are
/// `truth` (none when the place is not in the map).
QueryRecord queryRecordOf(int query_index, std::vector<int> truth, const Match& match, double time_ms);

/// One point of a precision-recall curve.
struct PrPoint {
  double threshold = 0.0;  ///< Queries with confidence >= threshold are accepted.
  double precision = 1.0;  ///< Correct accepted / accepted.
  double recall = 0.0;     ///< Correct accepted / queries about places in the map (queriesInMap()).
};

/// The figures of an evaluation (NaN where undefined, e.g. the median of nothing).
struct EvaluationSummary {
  int tolerance = 0;
  int queries = 0;
  /// Queries whose place is in the map (with true reference frames): the denominator of top1 and of
  /// every recall, as in VPR's Recall@1 (a query about a place outside the map has no right answer,
  /// and refusing it is right). top1, pr_auc and the recalls are NaN when there is none.
  int queries_in_map = 0;
  double top1 = 0.0;
  /// Average precision of the curve of precisionRecallCurve(); NaN (as recall_at_100_precision) when
  /// the curve has fewer than 2 points: every confidence equal ranks nothing.
  double pr_auc = 0.0;
  double recall_at_100_precision = 0.0;
  int accepted = 0;                ///< Answers that passed the acceptance rule.
  double accepted_rate = 0.0;      ///< accepted / queries: for queries outside the map, the false-closure rate.
  /// Correct accepted / accepted: NaN when nothing was accepted.
  double accepted_precision = std::numeric_limits<double>::quiet_NaN();
  double accepted_recall = 0.0;    ///< Correct accepted / queries_in_map.
  /// How far the wrong accepted answers lie: the largest distance of one from its nearest true frame
  /// [frames]. NaN when no accepted answer about a place in the map is wrong (an answer about a place
  /// outside it has no distance; accepted_rate counts those).
  double largest_wrong_accepted_error = std::numeric_limits<double>::quiet_NaN();
  double median_abs_error = std::numeric_limits<double>::quiet_NaN();
  double median_time_ms = std::numeric_limits<double>::quiet_NaN();
  double total_time_s = 0.0;  ///< Sum of the queries' times; a caller may replace it by a wall time.
};

/// Which frames of a traversal became keyframes: keyframe k is frame frames[k], and it stands for the
/// frames after it up to the next keyframe's (they were too similar to it to be kept).
struct Keyframes {
  std::vector<int> frames;  ///< Frame of each keyframe, increasing.
  int total = 0;            ///< Frames of the traversal.

  /// The last frame keyframe `keyframe` stands for.
  int lastFrameOf(int keyframe) const;
};

/// The record of `match` to the query localising frame `query_frame`, whose reference_index is a
/// keyframe of `reference`: predicted_index is that keyframe's frame and predicted_last the last frame
/// it stands for, so that an answer is right when the true frame is among the frames it stands for.
QueryRecord keyframeRecordOf(int query_frame, std::vector<int> truth, const Match& match, const Keyframes& reference,
                             double time_ms);

/// Distance from the predicted frames (predicted_index .. predicted_last) to the nearest true index; -1
/// when there is no prediction or no truth.
int absoluteError(const QueryRecord& record);

/// The true index nearest to the predicted frames (the first listed without a prediction); -1 without truth.
int nearestTrueIndex(const QueryRecord& record);

/// A prediction is correct when it lies within `tolerance` frames of any true index.
bool isCorrect(const QueryRecord& record, int tolerance);

/// Queries whose place is in the map: those with true reference frames.
int queriesInMap(const std::vector<QueryRecord>& records);

/// Fraction of the queries in the map whose prediction is correct (VPR's Recall@1); NaN when no
/// query's place is in the map.
double top1Accuracy(const std::vector<QueryRecord>& records, int tolerance);

/**
 * Precision-recall curve over a threshold on confidence, one point per distinct confidence, from
 * the highest threshold down. Queries without a prediction are never accepted. Recall is correct
 * accepted / queriesInMap(): a query without a prediction or answered wrongly counts against it, one
 * whose place lies outside the map (no true index) only against precision, when it is accepted, as
 * VPR benchmarks count false positives and negatives. NaN when no query's place is in the map.
 * Throws std::invalid_argument when tolerance < 0.
 */
std::vector<PrPoint> precisionRecallCurve(const std::vector<QueryRecord>& records, int tolerance);

/**
 * Area under the PR curve as average precision: sum over the curve's points of (R_k - R_{k-1}) * P_k,
 * with R_0 = 0, the step-wise formula of scikit-learn's average_precision_score. The recall is the
 * curve's, over the queries in the map, so the area never exceeds top-1. average_precision_score fed "is this
 * answer right" as labels divides by the right answers only and gives a much higher figure (0.997
 * where this gives 0.814: doc/results.md's thumbnail Nordland run, ds = 10).
 * No interpolation, so it does not reward the optimistic straight lines of the trapezoidal rule.
 */
double averagePrecision(const std::vector<PrPoint>& curve);

/// Highest recall among the curve's points whose precision is exactly 1 (0 when there is none).
double recallAtFullPrecision(const std::vector<PrPoint>& curve);

/// Median (mean of the two middle values for an even count); NaN for no values.
double median(std::vector<double> values);

/// Every figure of the summary; total_time_s is the sum of the records' times.
EvaluationSummary summarise(const std::vector<QueryRecord>& records, int tolerance);

/**
 * Per-frame protocol: the query frames (ascending) that have a full test sequence of
 * params.sequence_length frames inside a query of `query_frames` frames, with params.alignment.
 */
std::vector<int> perFrameQueries(int query_frames, const SequenceParams& params);

/// A test sequence of the global localisation protocol: query frames [start, start + length).
struct TestSequence {
  int start = 0;
  int length = 0;
  int query_index = 0;  ///< The frame localised: the newest, or the middle when centred.
};

/**
 * Global localisation protocol: `count` test sequences of `length` frames at random start positions
 * in a query of `query_frames` frames, drawn with std::mt19937_64 seeded with `seed` (same seed, same
 * positions on every platform). Positions are distinct when count <= query_frames - length + 1;
 * otherwise every position is used and the rest are drawn again. Returned in ascending start order.
 * Throws std::invalid_argument when length < 1, count < 0 or length > query_frames.
 */
std::vector<TestSequence> globalQueries(int query_frames, int length, int count, std::uint64_t seed,
                                        WindowAlignment alignment = WindowAlignment::kCausal);
/// What to tell a user whose globalQueries() repeat positions (count > query_frames - length + 1), as
/// the summary then counts a repeated test sequence again; empty when every position is distinct.
std::string repeatedGlobalQueries(int query_frames, int length, int count);

/// Whether the acceptance rule left `match`'s confidence at 0 because the map holds fewer than
/// kMinRivalEnds trajectory ends outside its window (acceptance.hpp).
bool hasTooFewRivals(const Match& match);
/// What to tell a user of the `too_few` of `answers` answers that hasTooFewRivals() in a map of
/// `map_keyframes`, so that a small map's figures (none accepted, no PR curve) do not look like a method
/// that fails; empty when there are none.
std::string tooFewRivalsNote(int too_few, int answers, int map_keyframes);

/**
 * Throws std::invalid_argument naming the query row when ground truth lists a query frame outside
 * [0, query_frames) or a reference frame outside [0, reference_frames): a file for other traversals
 * would otherwise give a summary that looks meaningful and is not.
 */
void checkGroundTruth(const GroundTruth& ground_truth, int query_frames, int reference_frames);

/**
 * Truth for a query frame: its ground-truth entry when `ground_truth` is given (nothing when the frame
 * has no entry), else the identity alignment {query_index} (nothing when query_index >= reference_frames).
 */
std::optional<std::vector<int>> truthFor(int query_index, const GroundTruth* ground_truth,
                                         int reference_frames);

}  // namespace mrs_vpr
