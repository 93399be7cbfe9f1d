#include "robustness_rows.hpp"

#include <chrono>
#include <string>
#include <vector>

#include "mrs_vpr/evaluation/evaluation.hpp"
#include "mrs_vpr/place_recognizer.hpp"
#include "first_pass_matcher.hpp"
#include "query_records.hpp"

namespace mrs_vpr {
namespace benchmark {

void runOtherWorld(const RealFrames& frames, const DescriptorSequence& summer, const DescriptorSequence& winter,
                   const mrs_vpr::DescriptorExtractor& extractor, const mrs_vpr::Parameters& params,
                   const RealBenchmarkOptions& options, int part_begin, int part_end, Report& report) {
  const Reference nordland = stretchOf(summer, 0, summer.size());
  Reference corridor{"corridor", describe(frames.corridor, extractor), {}};
  corridor.route_frame.assign(static_cast<std::size_t>(corridor.descriptors.size()), -1);
  for (int length : options.per_frame_lengths) {
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

void runSmallMaps(const DescriptorSequence& summer, const DescriptorSequence& winter, const mrs_vpr::Parameters& params,
                  const RealBenchmarkOptions& options, int part_begin, int part_end, int other_begin, int other_end,
                  bool out_of_map, Report& report) {
  constexpr int kStretches = 3;
  const auto stretchBegin = [](int low, int high, int size, int i) {
    return low + i * (high - low - size) / (kStretches - 1);
  };
  for (int length : options.per_frame_lengths) {
    const mrs_vpr::Parameters per_frame = perFrameParams(params, length);
    for (int size : {20, 50, 100, 150, 200, 300}) {
      // A map must be longer than its test sequences and fit in the part (and the other part) of the route.
      const bool fits = size <= part_end - part_begin && (!out_of_map || size <= other_end - other_begin);
      if (size <= length || !fits) continue;
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
  // The map keeps MRS's coarse cells, as the node's map does, so that no timed query computes them.
  DescriptorSequence map = summer;
  map.keepCoarseCells(params.mrs.levels, params.descriptor);
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
        const auto records = globalRecords(*matcher, map.view(), query, ends, length, truth_of, nullptr,
                                           options.tolerance, params.sequence.accept_threshold);
        report.row("global winter " + replay.name + " N=" + std::to_string(length) + " M=" + std::to_string(map.size()),
                   method, mrs_vpr::summarise(records, options.tolerance), {"global", false, map.size(), length});
      }
    }
    for (int length : options.per_frame ? options.per_frame_lengths : std::vector<int>{}) {
      const mrs_vpr::Parameters per_frame = perFrameParams(params, length);
      for (const std::string& method : options.methods) {
        const auto matcher = makeBenchMatcher(method, per_frame);
        const auto records = perFrameRecords(*matcher, map.view(), query.view(), truth_of);
        report.row("winter " + replay.name + " M=" + std::to_string(summer.size()) + " ds=" + std::to_string(length),
                   method, mrs_vpr::summarise(records, 2), {"per-frame", false, summer.size(), length});
      }
    }
  }
}

void runContinuous(const DescriptorSequence& summer, const DescriptorSequence& winter,
                   const mrs_vpr::Parameters& params, const RealBenchmarkOptions& options, int part_begin, int part_end,
                   Report& report) {
  // The first releases' continuous-mode length, kept so that these rows compare across releases; the
  // camera-drive rows (camera_drive_rows.hpp) run continuous mode at the node's defaults.
  constexpr int kLength = 10;
  const mrs_vpr::Parameters continuous = perFrameParams(params, kLength);
  const int route = summer.size();
  for (const std::string& method : options.methods) {
    if (method == "mrs-first-pass") continue;  // Not a method of PlaceRecognizer, whose mrs takes it where it pays.
    mrs_vpr::PlaceRecognizer recognizer(continuous);
    const int first_query = recognizer.fewestFramesForRecent(kLength);
    std::vector<QueryRecord> first_traversal;
    std::vector<QueryRecord> revisit;
    const int frames = route + part_end - part_begin;
    for (int t = 0; t < frames; ++t) {
      const bool second = t >= route;
      const int route_frame = second ? part_begin + t - route : t;
      recognizer.addDescriptor((second ? winter : summer).descriptorRow(route_frame));
      if (t + 1 < first_query) continue;
      // A test sequence that still holds summer frames is about neither traversal.
      if (second && t < route + kLength - 1) continue;
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

}  // namespace benchmark
}  // namespace mrs_vpr
