#include "query_records.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "mrs_vpr/evaluation/evaluation.hpp"
#include "mrs_vpr/mrs_matcher.hpp"
#include "first_pass_matcher.hpp"

namespace mrs_vpr {
namespace benchmark {

std::vector<QueryRecord> globalRecords(const mrs_vpr::SequenceMatcher& matcher, mrs_vpr::SequenceView map,
                                       const DescriptorSequence& query, const std::vector<int>& ends, int length,
                                       const std::function<std::vector<int>(int)>& truth_of, TruthDiagnosis* diagnosis,
                                       int tolerance, double accept_threshold) {
  std::vector<QueryRecord> records;
  const auto* mrs = dynamic_cast<const mrs_vpr::MrsMatcher*>(&matcher);
  const auto* first_pass = dynamic_cast<const FirstPassMatcher*>(&matcher);
  for (int end : ends) {
    const mrs_vpr::SequenceView test = query.view(end - length + 1, end + 1);
    const auto start = std::chrono::steady_clock::now();
    const mrs_vpr::Match match = matcher.match(map, test);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const QueryRecord& record = records.emplace_back(mrs_vpr::queryRecordOf(end, truth_of(end), match, ms));
    if (diagnosis == nullptr) continue;
    // Traced in a second, untimed search (the same answer: the search is seeded), so that the time is
    // of the same work as the other method's.
    std::vector<mrs_vpr::MrsLevelTrace> trace;
    if (mrs != nullptr) mrs->match(map, test, &trace);
    if (first_pass != nullptr) first_pass->match(map, test, &trace);
    diagnosis->add(trace, record.true_indices, tolerance, accept_threshold);
  }
  return records;
}

namespace {

/// Answers are judged by their distance in map frames from a true frame, and the 9k reference's
/// distractors follow its true places directly: an answer on one of the first distractors can lie
/// within the tolerance of the last true frames. Such answers are wrong places counted right; this
/// says when there are any, so that no figure hides them.
void reportDistractorsCountedRight(const std::string& method, const Reference& reference,
                                   const std::vector<QueryRecord>& records, int tolerance) {
  int counted_right = 0;
  for (const QueryRecord& record : records) {
    if (record.predicted_index < 0 || !mrs_vpr::isCorrect(record, tolerance)) continue;
    if (reference.route_frame[static_cast<std::size_t>(record.predicted_index)] < 0) ++counted_right;
  }
  if (counted_right > 0) {
    std::fprintf(stderr, "note: %s: %d answers on distractor frames next to the true places count as right\n",
                 method.c_str(), counted_right);
  }
}

}  // namespace

std::vector<QueryRecord> runGlobal(const mrs_vpr::SequenceMatcher& matcher, const Reference& reference,
                                   const DescriptorSequence& query, const std::vector<int>& ends, int length,
                                   bool out_of_map, TruthDiagnosis* diagnosis, int tolerance, double accept_threshold) {
  const auto records = globalRecords(
      matcher, reference.descriptors.view(), query, ends, length,
      [&](int end) { return out_of_map ? std::vector<int>{} : truthOf(reference, end); },
      out_of_map ? nullptr : diagnosis, tolerance, accept_threshold);
  if (!out_of_map) reportDistractorsCountedRight(matcher.name(), reference, records, tolerance);
  if (out_of_map && std::getenv("MRS_VPR_SHOW_FALSE") != nullptr) {
    for (const QueryRecord& record : records) {
      if (!record.accepted) continue;
      std::fprintf(stderr, "false closure: %s N=%d query end %d -> reference %d (route frame %d), confidence %.2f\n",
                   matcher.name().c_str(), length, record.query_index, record.predicted_index,
                   reference.route_frame[static_cast<std::size_t>(record.predicted_index)], record.confidence);
    }
  }
  return records;
}

mrs_vpr::Parameters perFrameParams(const mrs_vpr::Parameters& params, int length) {
  mrs_vpr::Parameters per_frame = params;
  per_frame.sequence.sequence_length = length;
  per_frame.sequence.velocity_step = 0.1;
  return per_frame;
}

std::vector<QueryRecord> perFrameRecords(const mrs_vpr::SequenceMatcher& matcher, mrs_vpr::SequenceView map,
                                         mrs_vpr::SequenceView query,
                                         const std::function<std::vector<int>(int)>& truth_of) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<mrs_vpr::Match> matches = matcher.matchEveryFrame(map, query);
  const double total_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  std::vector<QueryRecord> records;
  for (int i = 0; i < query.count; ++i) {
    const mrs_vpr::Match& match = matches[static_cast<std::size_t>(i)];
    if (match.reference_index < 0 && match.comparisons == 0) continue;  // No full sequence.
    records.push_back(mrs_vpr::queryRecordOf(i, truth_of(i), match, 0.0));
  }
  // The time is the searched frames': a frame without a full sequence costs nothing.
  for (QueryRecord& record : records) record.time_ms = total_ms / static_cast<double>(records.size());
  return records;
}

std::vector<QueryRecord> runPerFrame(const mrs_vpr::SequenceMatcher& matcher, const Reference& reference,
                                     const DescriptorSequence& query, int first, int last, bool out_of_map) {
  auto records = perFrameRecords(matcher, reference.descriptors.view(), query.view(first, last), [&](int i) {
    return out_of_map ? std::vector<int>{} : truthOf(reference, first + i);
  });
  for (QueryRecord& record : records) record.query_index += first;
  if (!out_of_map) reportDistractorsCountedRight(matcher.name(), reference, records, 2);
  return records;
}

std::vector<int> queryEnds(int low, int high, int length, int count, std::uint64_t seed) {
  const int first_end = low + length - 1;
  const std::vector<mrs_vpr::TestSequence> tests =
      mrs_vpr::globalQueries(high - first_end + 1, 1, count, seed);  // Positions in [0, span).
  std::vector<int> ends;
  for (const mrs_vpr::TestSequence& test : tests) ends.push_back(first_end + test.start);
  return ends;
}

}  // namespace benchmark
}  // namespace mrs_vpr
