#include "map_scale_rows.hpp"

#include <algorithm>
#include <cstdio>
#include <random>
#include <string>

#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/difference_matrix.hpp"
#include "mrs_vpr/mrs/recent_rows.hpp"
#include "mrs_vpr/node/continuous_queries.hpp"
#include "process_usage.hpp"
#include "row_tally.hpp"
#include "scale_map.hpp"
#include "tools/stopwatch.hpp"

namespace mrs_vpr {
namespace benchmark {

using tools::Clock;
using tools::secondsSince;

namespace {

constexpr double kPeriodSeconds = 1.0;  // launch/mrs_vpr.launch's auto_query_period

}  // namespace

mrs_vpr::Parameters paramsFor(int length, const mrs_vpr::DescriptorParams& descriptor) {
  mrs_vpr::Parameters params;
  if (length >= 128) params.sequence.velocity_step = 0.02;
  params.descriptor = descriptor;
  params.validate();
  return params;
}

void measureLength(const MapScaleOptions& options, mrs_vpr::PlaceRecognizer& recognizer, int length, double load_s,
                   double rss_per_frame, double peak_per_frame, const std::vector<cv::Mat>& winter,
                   const std::vector<cv::Mat>& summer) {
  const int frames = recognizer.size();
  // Two kinds of test sequence: winter (across seasons, the benchmark's hard case) and summer seen
  // again with a new shift, gain and noise (unambiguous, so that speed is timed on right answers).
  Augmenter augmenter(options.seed + 1);
  for (const bool across_seasons : {true, false}) {
    std::mt19937_64 rng(options.seed);
    std::uniform_int_distribution<int> end_of(length - 1, static_cast<int>(winter.size()) - 1);
    RowTally tally;
    for (int q = 0; q < options.queries; ++q) {
      const int end = end_of(rng);
      const Augmenter::Look look = augmenter.nextLook(2);
      mrs_vpr::DescriptorSequence query(recognizer.extractor().size());
      for (int i = end - length + 1; i <= end; ++i) {
        const auto frame = static_cast<std::size_t>(i);
        query.append(recognizer.describe(across_seasons ? winter[frame] : augmenter.apply(summer[frame], look)));
      }
      // The truth of the frame the answer localises (the middle one at the default centred alignment).
      const long long first_truth = options.truth_offset + end - length + 1;
      auto right = [&](const mrs_vpr::PlaceAnswer& answer) {
        return std::llabs(answer.match.reference_index - (first_truth + answer.localised_row)) <= 5;
      };
      const auto ask = [&](const char* method) { return recognizer.match(query, method); };
      if (q == 0) RowTally::warmUp(ask);
      const auto [mrs, answered] = tally.time(ask, q < options.brute_queries, right);
      if (answered) {
        const mrs_vpr::PlaceAnswer& brute = *answered;
        if (std::getenv("MRS_VPR_SHOW_ANSWERS") != nullptr) {
          std::fprintf(stderr, "N=%d %s query %d: truth %lld, mrs %d (confidence %.2f%s), brute %d (%.2f%s)\n", length,
                       across_seasons ? "winter" : "summer*", q, first_truth + mrs.localised_row,
                       mrs.match.reference_index, mrs.match.confidence, mrs.match.accepted ? ", accepted" : "",
                       brute.match.reference_index, brute.match.confidence, brute.match.accepted ? ", accepted" : "");
        }
      }
    }
    tally.print(sizeName(frames), length, across_seasons ? "winter" : "summer*", load_s, rss_per_frame, peak_per_frame);
  }
}

void measureContinuous(const MapScaleOptions& options, mrs_vpr::PlaceRecognizer& recognizer,
                       const std::vector<cv::Mat>& winter) {
  const int length = recognizer.parameters().sequence.sequence_length;
  const int needed = options.periods * options.keyframes_per_period + length;
  if (needed > static_cast<int>(winter.size())) throw std::invalid_argument("--periods: too many for the route");
  std::vector<cv::Mat> keyframes;
  for (int i = 0; i < needed; ++i) keyframes.push_back(recognizer.describe(winter[static_cast<std::size_t>(i)]));
  for (const std::string method : {"mrs", "seqslam"}) {
    // The same keyframes for both methods: the first `length` before the first query.
    const int base = recognizer.size();
    for (int i = 0; i < length; ++i) recognizer.addDescriptor(keyframes[static_cast<std::size_t>(i)]);
    recognizer.flush();
    double cpu = 0.0;
    double late_cpu = 0.0;  // Over the last half of the periods: after the rows have filled in.
    const int late_from = options.periods - options.periods / 2;
    std::vector<double> wall_ms;
    int accepted = 0;
    int asked_at_size = recognizer.size();
    double last_ms = 0.0;
    for (int period = 0; period < options.periods; ++period) {
      for (int k = 0; k < options.keyframes_per_period; ++k) {
        recognizer.addDescriptor(
            keyframes[static_cast<std::size_t>(length + period * options.keyframes_per_period + k)]);
      }
      recognizer.flush();
      const int size = recognizer.size();
      const std::vector<int> ends = mrs_vpr::node::continuousQueryEnds(
          asked_at_size, size, 0, mrs_vpr::node::affordableQueries(kPeriodSeconds, last_ms));
      asked_at_size = size;
      for (const int end : ends) {
        const double cpu_start = processCpuSeconds();
        const auto start = Clock::now();
        const mrs_vpr::PlaceAnswer answer = recognizer.matchRecent(length, method, nullptr, end);
        last_ms = secondsSince(start) * 1e3;
        wall_ms.push_back(last_ms);
        const double spent = processCpuSeconds() - cpu_start;
        cpu += spent;
        if (period >= late_from) late_cpu += spent;
        accepted += answer.match.accepted ? 1 : 0;
      }
    }
    const int localisable = options.periods * options.keyframes_per_period;
    std::printf(
        "%9s %5d %8s continuous mode: %d keyframes a period, %s: %.1f%% of a core at a 1 s period "
        "(%.1f%% over the last %d periods; median query %.1f ms), %zu of %d keyframes localised, %d accepted\n",
        sizeName(base).c_str(), length, method.c_str(), options.keyframes_per_period, method.c_str(),
        100.0 * cpu / options.periods, 100.0 * late_cpu / std::max(1, options.periods - late_from),
        options.periods - late_from, upperMedianOf(wall_ms), wall_ms.size(), localisable, accepted);
    std::fflush(stdout);
    // The next method starts from the same map: drop what was added by reloading is too slow, so the
    // second method's map is longer by these keyframes (a few dozen frames of a large map).
  }
}

int recentRouteFrames(const MapScaleOptions& options, int length) {
  return 2 * length + options.queries + options.brute_queries * length;
}

void measureRecent(const MapScaleOptions& options, mrs_vpr::PlaceRecognizer& recognizer, int length, double load_s,
                   double rss_per_frame, double peak_per_frame, const std::vector<cv::Mat>& winter,
                   int& next_route_frame) {
  std::vector<int> route_frame_of;  // Of each map frame added here, from the map's size before.
  const int base = recognizer.size();
  const auto addKeyframes = [&](int count) {
    if (next_route_frame + count > static_cast<int>(winter.size())) {
      throw std::invalid_argument("--lengths/--queries: the route in winter is too short for the recent rows");
    }
    for (int i = 0; i < count; ++i, ++next_route_frame) {
      recognizer.addDescriptor(recognizer.describe(winter[static_cast<std::size_t>(next_route_frame)]));
      route_frame_of.push_back(next_route_frame);
    }
    recognizer.flush();
  };
  struct Kind {
    const char* name;
    int new_keyframes;  ///< Before each question.
  };
  for (const Kind kind : {Kind{"recent", 1}, Kind{"recent=", 0}, Kind{"recent*", length}}) {
    const bool rows_kept = kind.new_keyframes < length;
    if (kind.new_keyframes == 1) {
      // Not timed: as continuous mode does, a question after each keyframe, until the rows kept cover a
      // whole test sequence.
      addKeyframes(length);
      for (int i = 0; i < length; ++i) {
        addKeyframes(1);
        recognizer.matchRecent(length, "mrs");
      }
    }
    const int asked = rows_kept ? options.queries : options.brute_queries;
    const auto ask = [&](const char* method) { return recognizer.matchRecent(length, method); };
    RowTally::warmUp(ask);  // before the first question's new keyframes, whose rows it would compute
    RowTally tally;
    for (int q = 0; q < asked; ++q) {
      addKeyframes(kind.new_keyframes);
      const int first = recognizer.size() - length;
      auto right = [&](const mrs_vpr::PlaceAnswer& answer) {
        const int route_frame = route_frame_of[static_cast<std::size_t>(first + answer.localised_row - base)];
        return std::llabs(answer.match.reference_index - (options.truth_offset + route_frame)) <= 5;
      };
      tally.time(ask, q < options.brute_queries, right);
    }
    tally.print(sizeName(base), length, kind.name, load_s, rss_per_frame, peak_per_frame);
  }
}

void measureMapStream(const mrs_vpr::PlaceRecognizer& recognizer, int frames) {
  mrs_vpr::DescriptorSequence map(recognizer.state().descriptor_size);
  map.reserve(frames);
  recognizer.visitFrames(0, frames, [&](const cv::Mat& descriptor, mrs_vpr::Stamp) { map.append(descriptor); });
  const mrs_vpr::SequenceView newest = map.view().slice(frames - 1, frames);
  cv::Mat row(1, frames, CV_32F);
  std::vector<double> ms;
  for (int pass = 0; pass < 7; ++pass) {
    const auto start = Clock::now();
    mrs_vpr::computeDifferenceMatrix(newest, map.view(), row);
    ms.push_back(secondsSince(start) * 1e3);
  }
  const double bytes = static_cast<double>(frames) * map.descriptorSize();
  std::printf(
      "%9s  map stream: one keyframe against every map frame (a new keyframe's row), median of %zu: "
      "%.2f ms, %.1f GB/s of descriptors\n",
      sizeName(frames).c_str(), ms.size(), upperMedianOf(ms), bytes / (upperMedianOf(ms) * 1e-3) / 1e9);
  std::fflush(stdout);
}

}  // namespace benchmark
}  // namespace mrs_vpr
