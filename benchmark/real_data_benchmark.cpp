// Real-data benchmark: MRS-VPR against this package's brute-force SeqSLAM on real frames.
//
// Prints figures; it is not a test. It reads the Nordland summer/winter halves and the corridor set
// from a data folder at run time and builds:
//   - references of M ~ 1.8k (summer) and M ~ 9k (summer plus real distractors: both seasons
//     mirrored, summer played backwards, winter mirrored and backwards, the corridor frames);
//   - known-ground queries from winter (global protocol, N = 100, 200, 300; per-frame, ds = 10, 50 or
//     --per-frame-lengths);
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
//                          [--per-frame-lengths 10,50] [--references 1.8k,9k] [--threads 1] [--tolerance 5] [--seed 42]
//                          [--skip-per-frame] [--skip-global] [--skip-drives] [--drive-length L]
//                          [--drive-alignment-slack S] [--drive-accept-threshold C] [--diagnose] [--json FILE]

#include <algorithm>
#include <cstdio>
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
#include "mrs_vpr/sequence_matcher.hpp"
#include "tools/tool_main.hpp"
#include "camera_drive_rows.hpp"
#include "drive_seed_summary.hpp"
#include "first_pass_matcher.hpp"
#include "query_records.hpp"
#include "real_benchmark_options.hpp"
#include "real_references.hpp"
#include "real_report.hpp"
#include "robustness_rows.hpp"
#include "truth_diagnosis.hpp"

namespace mrs_vpr {
namespace benchmark {
namespace {

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
      for (int length : options.per_frame_lengths) {
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
