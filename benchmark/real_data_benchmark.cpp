// Real-data benchmark: MRS-VPR against this package's brute-force SeqSLAM on real frames.
//
// Prints figures; it is not a test. It reads the Nordland summer/winter halves and the corridor set
// from a data folder at run time and builds:
//   - references of M ~ 1.8k (summer) and M ~ 9k (summer plus real distractors: both seasons
//     mirrored, summer played backwards, winter mirrored and backwards, the corridor frames);
//   - known-ground queries from winter (global protocol, N = 100, 200, 300; per-frame, ds = 10, 50);
//   - out-of-map queries: winter frames of one half of the route against a reference built from the
//     other half only (its summer frames and the same kinds of distractors), so every accepted
//     answer is a false loop closure;
//   - small maps (20 to 300 frames, as a robot's map is when it starts), known ground and out of the map;
//   - the reported part's winter frames played backwards (places in the map that no trajectory follows);
//   - the node's continuous mode on one traversal (summer, then the part again in winter), its map
//     growing from empty;
//   - camera drives (camera_drive_rows.hpp): the summer frames and the part's winter frames replayed as
//     a camera-only vehicle records them, with noisy stops and slow and fast stretches, through the
//     node's continuous mode at its defaults and through the evaluator's per-frame protocol.
// The route is split in two parts, "tune" (first half) and "check" (second half): design choices are
// made on one and reported on the other (--part). Both methods answer the same queries in one run.
//
//   mrs_vpr_real_benchmark --data DIR [--part tune|check|all] [--queries 100] [--lengths 100,200,300]
//                          [--references 1.8k,9k] [--threads 1] [--tolerance 5] [--seed 42]
//                          [--skip-per-frame] [--skip-global] [--skip-drives] [--drive-length L]
//                          [--drive-alignment-slack S] [--drive-accept-threshold C] [--diagnose] [--json FILE]

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <iterator>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "mrs_vpr/descriptor.hpp"
#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/evaluation/evaluation.hpp"
#include "mrs_vpr/memory_reuse.hpp"
#include "mrs_vpr/mrs_matcher.hpp"
#include "mrs_vpr/place_recognizer.hpp"
#include "mrs_vpr/sequence_matcher.hpp"
#include "tools/tool_main.hpp"
#include "camera_drive_rows.hpp"
#include "drive_seed_summary.hpp"
#include "first_pass_matcher.hpp"
#include "real_benchmark_options.hpp"
#include "real_references.hpp"
#include "real_report.hpp"
#include "truth_diagnosis.hpp"

namespace mrs_vpr {
namespace benchmark {
namespace {

/// One method's answers to the test sequences of `length` frames of `query` that end at `ends`, in
/// `map`; the sequence ending at frame e has the true places truth_of(e). With `diagnosis`, MRS's
/// levels are traced into it.
std::vector<QueryRecord> globalRecords(const mrs_vpr::SequenceMatcher& matcher, mrs_vpr::SequenceView map,
                                       const DescriptorSequence& query, const std::vector<int>& ends, int length,
                                       const std::function<std::vector<int>(int)>& truth_of, TruthDiagnosis* diagnosis,
                                       int tolerance, double accept_threshold) {
  std::vector<QueryRecord> records;
  const auto* mrs = dynamic_cast<const mrs_vpr::MrsMatcher*>(&matcher);
  const auto* first_pass = dynamic_cast<const FirstPassMatcher*>(&matcher);
  for (int end : ends) {
    const mrs_vpr::SequenceView test = query.view(end - length + 1, end + 1);
    std::vector<mrs_vpr::MrsLevelTrace> trace;
    const auto start = std::chrono::steady_clock::now();
    const mrs_vpr::Match match = diagnosis == nullptr ? matcher.match(map, test)
                                 : mrs != nullptr     ? mrs->match(map, test, &trace)
                                 : first_pass != nullptr ? first_pass->match(map, test, &trace)
                                                         : matcher.match(map, test);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const QueryRecord& record = records.emplace_back(mrs_vpr::queryRecordOf(end, truth_of(end), match, ms));
    if (diagnosis != nullptr) diagnosis->add(trace, record.true_indices, tolerance, accept_threshold);
  }
  return records;
}

/// Runs one method on test sequences ending at the given frames of the route, in `reference`.
std::vector<QueryRecord> runGlobal(const mrs_vpr::SequenceMatcher& matcher, const Reference& reference,
                                   const DescriptorSequence& query, const std::vector<int>& ends, int length,
                                   bool out_of_map, TruthDiagnosis* diagnosis, int tolerance, double accept_threshold) {
  const auto records = globalRecords(
      matcher, reference.descriptors.view(), query, ends, length,
      [&](int end) { return out_of_map ? std::vector<int>{} : truthOf(reference, end); },
      out_of_map ? nullptr : diagnosis, tolerance, accept_threshold);
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

/// `params` for the per-frame rows: sequences of `length` frames at OpenSeqSLAM's velocity step 0.1,
/// enough for short sequences.
mrs_vpr::Parameters perFrameParams(const mrs_vpr::Parameters& params, int length) {
  mrs_vpr::Parameters per_frame = params;
  per_frame.sequence.sequence_length = length;
  per_frame.sequence.velocity_step = 0.1;
  return per_frame;
}

/// The answers to every frame of `query` with a full sequence, in `map`; frame i's true places are
/// `truth_of(i)`.
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
    records.push_back(mrs_vpr::queryRecordOf(i, truth_of(i), match, total_ms / query.count));
  }
  return records;
}

std::vector<QueryRecord> runPerFrame(const mrs_vpr::SequenceMatcher& matcher, const Reference& reference,
                                     const DescriptorSequence& query, int first, int last, bool out_of_map) {
  auto records = perFrameRecords(matcher, reference.descriptors.view(), query.view(first, last), [&](int i) {
    return out_of_map ? std::vector<int>{} : truthOf(reference, first + i);
  });
  for (QueryRecord& record : records) record.query_index += first;
  return records;
}

/// Out-of-map queries from another world: the corridor's frames against a map of the Nordland summer
/// frames, and Nordland winter frames of the reported part against a map of the corridor.
void runOtherWorld(const RealFrames& frames, const DescriptorSequence& summer, const DescriptorSequence& winter,
                   const mrs_vpr::DescriptorExtractor& extractor, const mrs_vpr::Parameters& params,
                   const RealBenchmarkOptions& options, int part_begin, int part_end, Report& report) {
  const Reference nordland = stretchOf(summer, 0, summer.size());
  Reference corridor{"corridor", describe(frames.corridor, extractor), {}};
  corridor.route_frame.assign(static_cast<std::size_t>(corridor.descriptors.size()), -1);
  for (int length : {10, 50}) {
    const mrs_vpr::Parameters per_frame = perFrameParams(params, length);
    for (const std::string& method : options.methods) {
      const auto matcher = makeBenchMatcher(method, per_frame);
      const int corridor_frames = corridor.descriptors.size();
      report.row("corridor in Nordland map ds=" + std::to_string(length), method,
                 mrs_vpr::summarise(runPerFrame(*matcher, nordland, corridor.descriptors, 0, corridor_frames, true), 2),
                 {"per-frame", true, nordland.descriptors.size(), length});
      report.row("Nordland in corridor map ds=" + std::to_string(length), method,
                 mrs_vpr::summarise(runPerFrame(*matcher, corridor, winter, part_begin, part_end, true), 2),
                 {"per-frame", true, corridor_frames, length});
    }
  }
}

/// Maps of a few to a few hundred frames: kStretches stretches of the summer frames of each size.
/// Known ground: stretches of the reported part, queried by the same stretch's winter frames. Out of
/// the map: stretches of the other part, queried by the whole reported part.
void runSmallMaps(const DescriptorSequence& summer, const DescriptorSequence& winter, const mrs_vpr::Parameters& params,
                  const RealBenchmarkOptions& options, int part_begin, int part_end, int other_begin, int other_end,
                  bool out_of_map, Report& report) {
  constexpr int kStretches = 3;
  const auto stretchBegin = [](int low, int high, int size, int i) {
    return low + i * (high - low - size) / (kStretches - 1);
  };
  for (int length : {10, 50}) {
    const mrs_vpr::Parameters per_frame = perFrameParams(params, length);
    for (int size : {20, 50, 100, 150, 200, 300}) {
      if (size <= length) continue;
      const std::string setting = " M=" + std::to_string(size) + " ds=" + std::to_string(length);
      for (const std::string& method : options.methods) {
        const auto matcher = makeBenchMatcher(method, per_frame);
        std::vector<QueryRecord> known;
        std::vector<QueryRecord> unknown;
        for (int i = 0; i < kStretches; ++i) {
          const int begin = stretchBegin(part_begin, part_end, size, i);
          const auto records =
              runPerFrame(*matcher, stretchOf(summer, begin, begin + size), winter, begin, begin + size, false);
          known.insert(known.end(), records.begin(), records.end());
          if (!out_of_map) continue;
          const int other = stretchBegin(other_begin, other_end, size, i);
          const auto wrong =
              runPerFrame(*matcher, stretchOf(summer, other, other + size), winter, part_begin, part_end, true);
          unknown.insert(unknown.end(), wrong.begin(), wrong.end());
        }
        report.row("small maps" + setting, method, mrs_vpr::summarise(known, 2), {"per-frame", false, size, length});
        if (!out_of_map) continue;
        report.row("out-of-map small maps" + setting, method, mrs_vpr::summarise(unknown, 2),
                   {"per-frame", true, size, length});
      }
    }
  }
}

/// Seeded ends of test sequences of `length` frames that lie wholly inside frames [low, high], so that
/// out-of-map queries share no frame with the other part's reference.
std::vector<int> queryEnds(int low, int high, int length, int count, std::uint64_t seed) {
  const int first_end = low + length - 1;
  const std::vector<mrs_vpr::TestSequence> tests =
      mrs_vpr::globalQueries(high - first_end + 1, 1, count, seed);  // Positions in [0, span).
  std::vector<int> ends;
  for (const mrs_vpr::TestSequence& test : tests) ends.push_back(first_end + test.start);
  return ends;
}

/// The reported part's winter frames replayed at speeds the route was not driven at, against the
/// summer frames of the whole route: backwards, at twice the speed (every other frame), at half
/// (every frame twice), and stopping for kStopFrames frames (one second at 30 Hz) after every
/// kStopEvery. Every place is in the map, but the default velocities (0.8 to 1.2 map frames a query
/// frame) fit none of these, or a stop only in part. Per-frame rows at ds = 10 and 50, global rows
/// at the benchmark's lengths, scored against the true places: an accepted answer must still be right.
void runReplays(const DescriptorSequence& summer, const DescriptorSequence& winter, const mrs_vpr::Parameters& params,
                const RealBenchmarkOptions& options, int part_begin, int part_end, Report& report) {
  struct Replay {
    std::string name;
    std::vector<int> frames;  ///< The winter frame of each replayed frame.
  };
  constexpr int kStopEvery = 100;
  constexpr int kStopFrames = 30;
  std::vector<Replay> replays{
      {"backwards", {}}, {"at twice the speed", {}}, {"at half the speed", {}}, {"with stops", {}}};
  for (int frame = part_end - 1; frame >= part_begin; --frame) replays[0].frames.push_back(frame);
  for (int frame = part_begin; frame < part_end; frame += 2) replays[1].frames.push_back(frame);
  for (int frame = part_begin; frame < part_end; ++frame) {
    replays[2].frames.insert(replays[2].frames.end(), 2, frame);
    const bool stop = (frame - part_begin) % kStopEvery == kStopEvery - 1;
    replays[3].frames.insert(replays[3].frames.end(), stop ? 1 + kStopFrames : 1, frame);
  }
  for (const Replay& replay : replays) {
    DescriptorSequence query(winter.descriptorSize());
    for (const int frame : replay.frames) query.append(winter.descriptorRow(frame));
    const auto truth_of = [&](int i) { return std::vector<int>{replay.frames[static_cast<std::size_t>(i)]}; };
    // Global queries, as a robot's ~query of N frames: the same seeded ends for both methods.
    for (int length : options.global ? options.lengths : std::vector<int>{}) {
      const std::vector<int> ends = queryEnds(0, query.size() - 1, length, options.queries, options.seed);
      for (const std::string& method : options.methods) {
        const auto matcher = makeBenchMatcher(method, params);
        const auto records = globalRecords(*matcher, summer.view(), query, ends, length, truth_of, nullptr,
                                           options.tolerance, params.sequence.accept_threshold);
        report.row("global winter " + replay.name + " N=" + std::to_string(length) + " M=" +
                       std::to_string(summer.size()),
                   method, mrs_vpr::summarise(records, options.tolerance), {"global", false, summer.size(), length});
      }
    }
    for (int length : options.per_frame ? std::vector<int>{10, 50} : std::vector<int>{}) {
      const mrs_vpr::Parameters per_frame = perFrameParams(params, length);
      for (const std::string& method : options.methods) {
        const auto matcher = makeBenchMatcher(method, per_frame);
        const auto records = perFrameRecords(*matcher, summer.view(), query.view(), truth_of);
        report.row("winter " + replay.name + " M=" + std::to_string(summer.size()) + " ds=" + std::to_string(length),
                   method, mrs_vpr::summarise(records, 2), {"per-frame", false, summer.size(), length});
      }
    }
  }
}

/// The node's continuous mode on one traversal: a robot drives the whole route in summer, then the
/// reported part again in winter, and after every frame asks where its newest `length` frames lie
/// among the older ones (PlaceRecognizer::matchRecent, the node's default recent_exclusion). On the
/// first traversal no place comes back, so every accepted answer is a false loop closure; on the
/// second, the summer frame of the same place is the truth. The map starts empty and grows.
void runContinuous(const DescriptorSequence& summer, const DescriptorSequence& winter,
                   const mrs_vpr::Parameters& params, const RealBenchmarkOptions& options, int part_begin, int part_end,
                   Report& report) {
  constexpr int kLength = 10;  // The node's auto_query_frames default: sequence/sequence_length.
  const mrs_vpr::Parameters continuous = perFrameParams(params, kLength);
  const int route = summer.size();
  for (const std::string& method : options.methods) {
    if (method == "mrs-first-pass") continue;  // Not a method of PlaceRecognizer, whose mrs takes it where it pays.
    mrs_vpr::PlaceRecognizer recognizer(continuous);
    const int first_query = 2 * kLength + recognizer.recognizerParameters().recent_exclusion;
    std::vector<QueryRecord> first_traversal;
    std::vector<QueryRecord> revisit;
    const int frames = route + part_end - part_begin;
    for (int t = 0; t < frames; ++t) {
      const bool second = t >= route;
      const int route_frame = second ? part_begin + t - route : t;
      recognizer.addDescriptor((second ? winter : summer).descriptorRow(route_frame));
      if (t + 1 < first_query) continue;
      const auto start = std::chrono::steady_clock::now();
      const mrs_vpr::Match match = recognizer.matchRecent(kLength, method).match;
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      // The summer frame of a place has the place's route index in the map.
      (second ? revisit : first_traversal)
          .push_back(mrs_vpr::queryRecordOf(t, second ? std::vector<int>{route_frame} : std::vector<int>{}, match, ms));
    }
    report.row("continuous, first traversal ds=10", method, mrs_vpr::summarise(first_traversal, 2),
               {"continuous", true, route, kLength});
    report.row("continuous, revisit in winter ds=10", method, mrs_vpr::summarise(revisit, 2),
               {"continuous", false, route, kLength});
  }
}

/// The camera drives (camera_drive_rows.hpp) of --drive-seeds seeds from --seed, then, for more than
/// one seed, the totals over them.
void runDrives(const RealFrames& frames, const RealBenchmarkOptions& options, int route, int part_begin, int part_end,
               Report& report) {
  CameraDriveInput drives;
  drives.summer = &frames.summer;
  drives.winter = &frames.winter;
  drives.route_frames = route;
  drives.part_begin = part_begin;
  drives.part_end = part_end;
  // The drives run through PlaceRecognizer, whose mrs takes the first pass where it pays.
  std::copy_if(options.methods.begin(), options.methods.end(), std::back_inserter(drives.methods),
               [](const std::string& method) { return method != "mrs-first-pass"; });
  if (drives.methods.size() < options.methods.size()) {
    std::fprintf(stderr, "camera drives: mrs-first-pass is not a method of the node, its drives are not run\n");
  }
  if (drives.methods.empty()) return;
  drives.descriptor = options.descriptor;
  if (options.drive_length > 0) drives.sequence.sequence_length = options.drive_length;
  drives.sequence.alignment_slack = options.drive_alignment_slack;
  drives.sequence.accept_threshold = options.drive_accept_threshold;
  drives.min_appearance_change = options.drive_min_appearance_change;
  drives.sequence.alignment = mrs_vpr::parseWindowAlignment(options.drive_alignment);
  drives.each_keyframe = options.drive_queries == "each";
  drives.sequence.velocity_min = options.velocity_min;
  drives.sequence.velocity_max = options.velocity_max;
  std::vector<nlohmann::json> continuous_rows;
  for (int k = 0; k < options.drive_seeds; ++k) {
    drives.seed = options.seed + static_cast<std::uint64_t>(k);
    runCameraDrives(
        drives,
        [&](const std::vector<nlohmann::json>& rows) {
          for (nlohmann::json row : rows) {
            row["seed"] = drives.seed;
            continuous_rows.push_back(row);
            report.add({row});
          }
        },
        [&](const std::string& setting, const std::string& method, const mrs_vpr::EvaluationSummary& summary,
            int reference_frames, int sequence_length) {
          report.row(setting, method, summary, {"per-frame", false, reference_frames, sequence_length});
        });
  }
  if (options.drive_seeds > 1) printDriveSeedSummary(continuous_rows);
}

int run(int argc, char** argv) {
  const std::optional<RealBenchmarkOptions> parsed = parseRealBenchmarkOptions(argc, argv);
  if (!parsed) return 0;
  const RealBenchmarkOptions& options = *parsed;
  cv::setNumThreads(options.threads);
  mrs_vpr::Parameters params;
  params.descriptor = options.descriptor;
  // Velocity step 0.02 for both methods: 0.1 leaves up to 15 frames of drift at N = 300, so neither
  // could align long sequences whose speed lies between two steps.
  params.sequence.velocity_step = 0.02;
  // The global and per-frame rows judge where a test sequence ends, as the paper does; the drive rows
  // localise what the node localises (--drive-alignment).
  params.sequence.alignment = mrs_vpr::WindowAlignment::kCausal;
  params.mrs.hypotheses = options.hypotheses;
  params.mrs.min_coarse_frames = options.min_coarse_frames;
  params.sequence.velocity_min = options.velocity_min;
  params.sequence.velocity_max = options.velocity_max;
  params.validate();
  const mrs_vpr::DescriptorExtractor extractor(params.descriptor);

  std::fprintf(stderr, "reading %s ...\n", options.data.c_str());
  const RealFrames frames = loadRealFrames(options.data);
  const int route = static_cast<int>(std::min(frames.summer.size(), frames.winter.size()));
  const int half = route / 2;
  const DescriptorSequence winter = describe(frames.winter, extractor);

  // The part whose queries are reported; out-of-map references come from the other part. The whole
  // route (--part all) leaves no other part: then there are no out-of-map rows.
  const bool out_of_map = options.part != "all";
  const int part_begin = options.part == "check" ? half : 0;
  const int part_end = options.part == "tune" ? half : route;
  const int other_begin = options.part == "check" ? 0 : half;
  const int other_end = options.part == "check" ? half : route;

  std::printf("Real-data benchmark: Nordland summer (reference) / winter (query), corridor; part '%s' "
              "(route frames %d..%d of %d), front end %s, threads %d, tolerance %d, velocities %.2f..%.2f step %.2f, "
              "seed %llu\n",
              options.part.c_str(), part_begin, part_end - 1, route, params.descriptor.describe().c_str(),
              options.threads, options.tolerance,
              params.sequence.velocity_min, params.sequence.velocity_max, params.sequence.velocity_step,
              static_cast<unsigned long long>(options.seed));
  std::printf("success = top-1 within tolerance; accepted = the core's acceptance rule at its default (%.1f)\n\n",
              params.sequence.accept_threshold);
  if (!out_of_map) std::printf("no out-of-map rows: --part all leaves no part of the route outside the map\n\n");
  Report::printHeader();
  Report report;

  std::vector<std::unique_ptr<mrs_vpr::SequenceMatcher>> matchers;
  for (const std::string& method : options.methods) matchers.push_back(makeBenchMatcher(method, params));
  for (const std::string& size : options.references) {
    const bool distractors = size == "9k";
    Reference known = buildReference(frames, extractor, 0, route, distractors, size);
    known.descriptors.keepCoarseCells(params.mrs.levels, params.descriptor);
    // The out-of-map reference: the other part of the route (with its own distractors), so that no
    // query frame of this part is in it.
    Reference unknown = buildReference(frames, extractor, other_begin, other_end, distractors, size + "-other");
    unknown.descriptors.keepCoarseCells(params.mrs.levels, params.descriptor);
    const std::string m = " M=" + std::to_string(known.descriptors.size());
    const std::string m_other = " M=" + std::to_string(unknown.descriptors.size());

    if (options.global) {
      for (int length : options.lengths) {
        const std::vector<int> ends = queryEnds(part_begin, part_end - 1, length, options.queries, options.seed);
        std::map<std::string, TruthDiagnosis> diagnoses;  // One per traced method.
        for (const auto& matcher : matchers) {
          const bool diagnose = options.diagnose && matcher->name() != "seqslam";
          const auto records = runGlobal(*matcher, known, winter, ends, length, false,
                                         diagnose ? &diagnoses[matcher->name()] : nullptr, options.tolerance,
                                         params.sequence.accept_threshold);
          report.row("global N=" + std::to_string(length) + m, matcher->name(),
                     mrs_vpr::summarise(records, options.tolerance),
                     {"global", false, known.descriptors.size(), length});
        }
        for (const auto& [name, diagnosis] : diagnoses) {
          diagnosis.print("N=" + std::to_string(length) + m + (name == "mrs" ? "" : " " + name));
        }
        for (const auto& matcher : matchers) {
          if (!out_of_map) break;
          const auto records = runGlobal(*matcher, unknown, winter, ends, length, true, nullptr, options.tolerance,
                                         params.sequence.accept_threshold);
          report.row("out-of-map global N=" + std::to_string(length) + m_other, matcher->name(),
                     mrs_vpr::summarise(records, options.tolerance),
                     {"global", true, unknown.descriptors.size(), length});
        }
      }
    }
    if (options.per_frame) {
      for (int length : {10, 50}) {
        const mrs_vpr::Parameters per_frame = perFrameParams(params, length);
        for (const std::string& method : options.methods) {
          const auto matcher = makeBenchMatcher(method, per_frame);
          const auto known_records = runPerFrame(*matcher, known, winter, part_begin, part_end, false);
          report.row("per-frame ds=" + std::to_string(length) + m + " tol 2", method,
                     mrs_vpr::summarise(known_records, 2), {"per-frame", false, known.descriptors.size(), length});
          if (!out_of_map) continue;
          const auto unknown_records = runPerFrame(*matcher, unknown, winter, part_begin, part_end, true);
          report.row("out-of-map per-frame ds=" + std::to_string(length) + m_other, method,
                     mrs_vpr::summarise(unknown_records, 2), {"per-frame", true, unknown.descriptors.size(), length});
        }
      }
    }
  }
  const DescriptorSequence summer = describe(frames.summer, extractor);
  if (options.per_frame) {
    runOtherWorld(frames, summer, winter, extractor, params, options, part_begin, part_end, report);
    runSmallMaps(summer, winter, params, options, part_begin, part_end, other_begin, other_end, out_of_map, report);
  }
  runReplays(summer, winter, params, options, part_begin, part_end, report);
  if (options.per_frame) runContinuous(summer, winter, params, options, part_begin, part_end, report);
  if (options.drives) runDrives(frames, options, route, part_begin, part_end, report);
  report.write(options.json, {{"part", options.part},
                              {"threads", options.threads},
                              {"tolerance", options.tolerance},
                              {"queries", options.queries},
                              {"seed", options.seed}});
  return 0;
}

}  // namespace
}  // namespace benchmark
}  // namespace mrs_vpr

int main(int argc, char** argv) {
  mrs_vpr::retainFreedMemory();  // As the node and the tools do.
  return mrs_vpr::tools::runTool("mrs_vpr_real_benchmark", mrs_vpr::benchmark::run, argc, argv);
}
