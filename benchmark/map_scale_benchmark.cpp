// Map-scale benchmark: load time, resident memory and query time of maps of 10k to 1M real frames.
//
// Prints figures; it is not a test. For each size it writes a map database (once; reused on later
// runs) of real frames: the Nordland summer half, as the true places, at a seeded position among
// distractors made of the shared real frames (Nordland turned upside down or by 180 degrees, and the
// corridor), in
// segments of a few hundred frames, each played forwards or backwards with its own shift, gain,
// offset and noise, so that the map is never a repetition of itself. Then a fresh process (so that
// nothing of the writing is resident) loads the map into a PlaceRecognizer and answers winter
// queries of N frames with both methods, side by side.
//
// Then continuous mode: frames of the route in winter join the map as keyframes, a few per period,
// and matchRecent answers once a period; the row gives the CPU time of those queries per period.
// Last, service questions about the map's newest frames ("recent" rows), both methods on one map.
//
//   mrs_vpr_map_scale_benchmark --data DIR [--sizes 10k,100k,1M] [--dir /tmp/mrs_vpr_map_scale]
//                               [--lengths 10,50,100,300] [--queries 5] [--brute-queries 2] [--threads 1]
//                               [--periods 20] [--keyframes-per-period 3] [--seed 42]

#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/difference_matrix.hpp"
#include "mrs_vpr/evaluation/image_folder.hpp"
#include "mrs_vpr/memory_reuse.hpp"
#include "mrs_vpr/mrs/recent_rows.hpp"
#include "mrs_vpr/node/continuous_queries.hpp"
#include "mrs_vpr/place_recognizer.hpp"
#include "mrs_vpr/store/map_database.hpp"
#include "tools/tool_main.hpp"
#include "map_scale_options.hpp"
#include "row_tally.hpp"
#include "scale_map.hpp"
#include "tools/stopwatch.hpp"

namespace mrs_vpr {
namespace benchmark {

using tools::Clock;
using tools::secondsSince;
namespace {

constexpr double kPeriodSeconds = 1.0;  // launch/mrs_vpr.launch's auto_query_period

/// Resident and peak resident memory of this process [bytes], from /proc/self/status.
std::pair<long long, long long> residentBytes() {
  std::ifstream status("/proc/self/status");
  long long rss = 0;
  long long hwm = 0;
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("VmRSS:", 0) == 0) rss = std::stoll(line.substr(6)) * 1024;
    if (line.rfind("VmHWM:", 0) == 0) hwm = std::stoll(line.substr(6)) * 1024;
  }
  return {rss, hwm};
}

/// CPU time of this process (every thread) [s].
double processCpuSeconds() {
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

/// The parameters of a query of `length` frames: the core's defaults (the node's), with the velocity
/// step of mrs_vpr_real_benchmark for sequences long enough to drift (0.1 leaves up to 15 frames of
/// drift at N = 300).
mrs_vpr::Parameters paramsFor(int length, const mrs_vpr::DescriptorParams& descriptor) {
  mrs_vpr::Parameters params;
  if (length >= 128) params.sequence.velocity_step = 0.02;
  params.descriptor = descriptor;
  params.validate();
  return params;
}

/// One map's rows for test sequences of `length` frames.
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
      const auto [mrs, answered] = tally.time([&](const char* method) { return recognizer.match(query, method); },
                                              q < options.brute_queries, right);
      if (answered) {
        const mrs_vpr::PlaceAnswer& brute = *answered;
        if (std::getenv("MRS_VPR_SHOW_ANSWERS") != nullptr) {
          std::fprintf(stderr, "N=%d %s query %d: truth %lld, mrs %d (confidence %.2f%s), brute %d (%.2f%s)\n", length,
                       across_seasons ? "winter" : "summer*", q, first_truth + mrs.localised_row, mrs.match.reference_index, mrs.match.confidence,
                       mrs.match.accepted ? ", accepted" : "", brute.match.reference_index, brute.match.confidence,
                       brute.match.accepted ? ", accepted" : "");
        }
      }
    }
    tally.print(sizeName(frames), length, across_seasons ? "winter" : "summer*", load_s, rss_per_frame,
                peak_per_frame);
  }
}

/// Continuous mode: keyframes of the route in winter join the map, keyframes_per_period between two
/// periods, and each period asks as the node's timer does (node/continuous_queries.hpp): a sequence of
/// the default length (sequence/sequence_length) ending at each new keyframe, within a fifth of the
/// period by the last question's time. Prints the questions' CPU time per 1 s period and how many of
/// the keyframes were localised, for both methods.
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
        recognizer.addDescriptor(keyframes[static_cast<std::size_t>(length + period * options.keyframes_per_period + k)]);
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
    std::printf("%9s %5d %8s continuous mode: %d keyframes a period, %s: %.1f%% of a core at a 1 s period "
                "(%.1f%% over the last %d periods; median query %.1f ms), %zu of %d keyframes localised, %d accepted\n",
                sizeName(base).c_str(), length, method.c_str(), options.keyframes_per_period, method.c_str(),
                100.0 * cpu / options.periods, 100.0 * late_cpu / std::max(1, options.periods - late_from),
                options.periods - late_from, upperMedianOf(wall_ms), wall_ms.size(), localisable, accepted);
    std::fflush(stdout);
    // The next method starts from the same map: drop what was added by reloading is too slow, so the
    // second method's map is longer by these keyframes (a few dozen frames of a large map).
  }
}

/// Route frames between continuous mode's keyframes and the recent rows'.
constexpr int kRouteGap = 100;

/// Frames of the route measureRecent adds for test sequences of `length` frames.
int recentRouteFrames(const MapScaleOptions& options, int length) {
  return 2 * length + options.queries + options.brute_queries * length;
}

/// Service questions about the map's newest frames (`~query {recent_frames: N}`, matchRecent): frames
/// of the route in winter join the map as keyframes, from `next_route_frame` on, and both methods
/// answer on the same map. Three kinds of row: "recent" asks after each new keyframe, as while
/// continuous mode runs, so that MRS has kept the rows of all but the newest frame
/// (mrs/recent_rows.hpp); "recent=" asks again with no new keyframe, as of a loaded map that is not
/// growing, so that MRS has every row; "recent*" asks after N new keyframes, none of whose rows it
/// has, so that it searches as for any test sequence.
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
    RowTally tally;
    for (int q = 0; q < asked; ++q) {
      addKeyframes(kind.new_keyframes);
      const int first = recognizer.size() - length;
      auto right = [&](const mrs_vpr::PlaceAnswer& answer) {
        const int route_frame = route_frame_of[static_cast<std::size_t>(first + answer.localised_row - base)];
        return std::llabs(answer.match.reference_index - (options.truth_offset + route_frame)) <= 5;
      };
      tally.time([&](const char* method) { return recognizer.matchRecent(length, method); },
                 q < options.brute_queries, right);
    }
    tally.print(sizeName(base), length, kind.name, load_s, rss_per_frame, peak_per_frame);
  }
}

/// How fast this machine streams the map: the differences of one keyframe to every map frame, which is
/// what a question with rows kept computes anew (the new keyframe's row). It reads every descriptor
/// once for one comparison each, so memory bandwidth, not arithmetic, sets its time; the brute force
/// makes N comparisons a descriptor read. The ratio of the two therefore differs from machine to
/// machine: the line tells what the "recent" rows' speed-up is made of here. On a copy of the map's
/// first `frames` frames (the map as loaded), taken after every other row, so that no other figure
/// includes it.
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
  std::printf("%9s  map stream: one keyframe against every map frame (a new keyframe's row), median of %zu: "
              "%.2f ms, %.1f GB/s of descriptors\n",
              sizeName(frames).c_str(), ms.size(), upperMedianOf(ms), bytes / (upperMedianOf(ms) * 1e-3) / 1e9);
  std::fflush(stdout);
}

/// The child: loads one map and answers the queries; prints its rows.
int measure(const MapScaleOptions& options) {
  cv::setNumThreads(options.threads);
  const mrs_vpr::DescriptorParams descriptor =
      mrs_vpr::MapDatabase(options.measure, mrs_vpr::MapAccess::kReadOnly).descriptorParams();
  const auto before = residentBytes();
  const auto load_start = Clock::now();
  mrs_vpr::RecognizerParams limits;
  limits.max_frames = 0;  // Unbounded: the largest maps measured may exceed the default capacity.
  limits.min_appearance_change = 0.0;  // The map's frames are keyframes already.
  mrs_vpr::PlaceRecognizer recognizer(paramsFor(10, descriptor), limits);
  {
    const mrs_vpr::MapDatabase map(options.measure, descriptor);
    recognizer.reserve(static_cast<int>(map.size()));
    map.forEachFrame([&](const mrs_vpr::StoredFrame& frame) { recognizer.addDescriptor(frame.descriptor, frame.stamp); });
    recognizer.flush();
  }
  const double load_s = secondsSince(load_start);
  const auto after = residentBytes();
  const int frames = recognizer.size();
  const double rss_per_frame = static_cast<double>(after.first - before.first) / frames;
  const double peak_per_frame = static_cast<double>(after.second) / frames;

  const std::vector<cv::Mat> winter = mrs_vpr::loadImageFolder(options.data + "/nordland/winter");
  const std::vector<cv::Mat> summer = mrs_vpr::loadImageFolder(options.data + "/nordland/summer");
  for (int length : options.lengths) {
    if (length >= 128) {
      // A recognizer with the long sequences' velocity step over the same frames (a view, not a copy,
      // is not offered by PlaceRecognizer: the map is loaded again into a second one).
      mrs_vpr::PlaceRecognizer fine(paramsFor(length, descriptor), limits);
      fine.reserve(frames);
      recognizer.visitFrames(0, frames, [&](const cv::Mat& d, mrs_vpr::Stamp stamp) { fine.addDescriptor(d, stamp); });
      fine.flush();
      measureLength(options, fine, length, load_s, rss_per_frame, peak_per_frame, winter, summer);
    } else {
      measureLength(options, recognizer, length, load_s, rss_per_frame, peak_per_frame, winter, summer);
    }
  }
  if (options.periods > 0) measureContinuous(options, recognizer, winter);
  // Past continuous mode's keyframes, with a gap of up to 100 places, so that no question finds those.
  const int continuous_frames = options.periods > 0 ? options.periods * options.keyframes_per_period +
                                                          recognizer.parameters().sequence.sequence_length
                                                    : 0;
  int recent_frames = 0;
  for (int length : options.lengths) {
    if (length < mrs_vpr::kMaxRecentRows) recent_frames += recentRouteFrames(options, length);
  }
  int next_route_frame = std::min(continuous_frames + kRouteGap, static_cast<int>(winter.size()) - recent_frames);
  if (next_route_frame < continuous_frames) {
    std::printf("%9s recent rows skipped: they need %d frames of the route in winter after continuous mode's %d, "
                "of %zu\n", sizeName(frames).c_str(), recent_frames, continuous_frames, winter.size());
    measureMapStream(recognizer, frames);
    return 0;
  }
  for (int length : options.lengths) {
    // Longer sequences take MRS's coarse levels, which keep nothing between queries.
    if (length < mrs_vpr::kMaxRecentRows) {
      measureRecent(options, recognizer, length, load_s, rss_per_frame, peak_per_frame, winter, next_route_frame);
    }
  }
  measureMapStream(recognizer, frames);
  return 0;
}

int run(int argc, char** argv) {
  const std::optional<MapScaleOptions> parsed = parseMapScaleOptions(argc, argv);
  if (!parsed) return 0;
  const MapScaleOptions& options = *parsed;
  if (!options.measure.empty()) return measure(options);

  ::mkdir(options.dir.c_str(), 0755);
  std::string lengths;
  for (int length : options.lengths) lengths += (lengths.empty() ? "" : ",") + std::to_string(length);
  std::printf("Map-scale benchmark: real frames (Nordland summer as the true places among augmented real "
              "distractors), queries of N = %s, %d per map (%d for brute force), threads %d, seed %llu;\n"
              "the core's default parameters, velocity step 0.02 from N = 128 on\n",
              lengths.c_str(), options.queries, options.brute_queries, options.threads,
              static_cast<unsigned long long>(options.seed));
  std::printf("queries: winter = the route in winter; summer* = summer with a new shift, gain and noise; "
              "recent = the map's newest N frames (the route in winter, added as keyframes) after one new keyframe, "
              "recent= = again with none (a map that is not growing), recent* = after N. "
              "load = database to a queryable map;\nRSS/frame = resident growth of the load; peak = the process's "
              "peak RSS over frames; right = within 5 frames; wrong/acc = mrs answers accepted and wrong / accepted;\n"
              "same = queries where mrs and brute force gave the same frame / the same acceptance / of those both "
              "answered; dconf = largest confidence difference\n\n");
  std::printf("%9s %5s %8s %8s %9s %9s %8s %10s %10s %8s %10s %10s %10s %6s\n", "map", "N", "queries", "load[s]",
              "RSS/frame", "peak/fr", "mrs[ms]", "brute[ms]", "mrs right", "speed-up", "brute rt", "wrong/acc",
              "same", "dconf");
  std::fflush(stdout);
  for (const long long frames : options.sizes) {
    const std::string path = options.dir + "/map-" + sizeName(frames) + "-" + options.descriptor.type + "-seed" +
                             std::to_string(options.seed) + ".db";
    const std::string offset_path = path + ".truth";
    long long truth_offset = -1;
    std::ifstream known(offset_path);
    struct stat info {};
    if (!(known >> truth_offset) || ::stat(path.c_str(), &info) != 0) {
      truth_offset = writeScaleMap(path, frames, options);
      if (std::rename((path + ".part").c_str(), path.c_str()) != 0) throw std::runtime_error("cannot rename " + path);
      std::ofstream(offset_path) << truth_offset << "\n";
    }
    // A fresh process, so that the figures hold only what loading and querying cost.
    const pid_t child = fork();
    if (child == 0) {
      const std::string exe = "/proc/self/exe";
      const std::vector<std::string> args = {
          "mrs_vpr_map_scale_benchmark", "--data", options.data, "--measure", path, "--truth-offset",
          std::to_string(truth_offset), "--lengths", lengths, "--queries",
          std::to_string(options.queries), "--brute-queries", std::to_string(options.brute_queries), "--threads",
          std::to_string(options.threads), "--periods", std::to_string(options.periods), "--keyframes-per-period",
          std::to_string(options.keyframes_per_period), "--seed", std::to_string(options.seed)};  // The map records its front end.
      std::vector<char*> argv_child;
      for (const std::string& arg : args) argv_child.push_back(const_cast<char*>(arg.c_str()));
      argv_child.push_back(nullptr);
      ::execv(exe.c_str(), argv_child.data());
      std::_Exit(127);
    }
    int status = 0;
    ::waitpid(child, &status, 0);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) throw std::runtime_error("measuring " + path + " failed");
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace
}  // namespace benchmark
}  // namespace mrs_vpr

int main(int argc, char** argv) {
  mrs_vpr::retainFreedMemory();  // As the node and the tools do.
  return mrs_vpr::tools::runTool("mrs_vpr_map_scale_benchmark", mrs_vpr::benchmark::run, argc, argv);
}
