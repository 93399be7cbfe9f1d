#pragma once

// The real-data benchmark's rows beyond the two protocols: places from another world, maps of a few
// hundred frames, the route replayed at speeds it was not driven at, and the node's continuous mode.

#include "mrs_vpr/descriptor.hpp"
#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/parameters.hpp"
#include "real_benchmark_options.hpp"
#include "real_references.hpp"
#include "real_report.hpp"

namespace mrs_vpr {
namespace benchmark {

/// Out-of-map queries from another world: the corridor's frames against a map of the Nordland summer
/// frames, and Nordland winter frames of the reported part against a map of the corridor.
void runOtherWorld(const RealFrames& frames, const DescriptorSequence& summer, const DescriptorSequence& winter,
                   const mrs_vpr::DescriptorExtractor& extractor, const mrs_vpr::Parameters& params,
                   const RealBenchmarkOptions& options, int part_begin, int part_end, Report& report);

/// Maps of a few to a few hundred frames: kStretches stretches of the summer frames of each size.
/// Known ground: stretches of the reported part, queried by the same stretch's winter frames. Out of
/// the map: stretches of the other part, queried by the whole reported part.
void runSmallMaps(const DescriptorSequence& summer, const DescriptorSequence& winter, const mrs_vpr::Parameters& params,
                  const RealBenchmarkOptions& options, int part_begin, int part_end, int other_begin, int other_end,
                  bool out_of_map, Report& report);

/// The reported part's winter frames replayed at speeds the route was not driven at, against the
/// summer frames of the whole route: backwards, at twice the speed (every other frame), at half
/// (every frame twice), and stopping for kStopFrames frames (one second at 30 Hz) after every
/// kStopEvery. Every place is in the map, but the default velocities (0.8 to 1.2 map frames a query
/// frame) fit none of these, or a stop only in part. Per-frame rows at ds = 10 and 50, global rows
/// at the benchmark's lengths, scored against the true places: an accepted answer must still be right.
void runReplays(const DescriptorSequence& summer, const DescriptorSequence& winter, const mrs_vpr::Parameters& params,
                const RealBenchmarkOptions& options, int part_begin, int part_end, Report& report);

/// The node's continuous mode on one traversal: a robot drives the whole route in summer, then the
/// reported part again in winter, and after every frame asks where its newest `length` frames lie
/// among the older ones (PlaceRecognizer::matchRecent, the node's default recent_exclusion). On the
/// first traversal no place comes back, so every accepted answer is a false loop closure; on the
/// second, the summer frame of the same place is the truth. The map starts empty and grows.
void runContinuous(const DescriptorSequence& summer, const DescriptorSequence& winter,
                   const mrs_vpr::Parameters& params, const RealBenchmarkOptions& options, int part_begin, int part_end,
                   Report& report);

}  // namespace benchmark
}  // namespace mrs_vpr
