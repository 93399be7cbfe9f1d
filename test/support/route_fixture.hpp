#pragma once

// Generated routes, each generated (and described) once per test program and shared by its tests.

#include <cstdint>
#include <cstdlib>
#include <vector>

#include "mrs_vpr/descriptor.hpp"
#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/parameters.hpp"
#include "mrs_vpr/synthetic_route.hpp"

namespace mrs_vpr {
namespace testing_support {

/// The front end the generated route is described with. Its frames are textures made for OpenSeqSLAM's
/// thumbnail, whose search and acceptance tests they serve; which front end suits real frames is
/// measured on real frames (doc/results.md), and the HOG front end has tests of its own.
inline DescriptorParams routeDescriptor() {
  DescriptorParams params;
  params.type = kThumbnailFrontEnd;
  return params;
}

/// The core's defaults with the route's front end.
inline Parameters routeParameters() {
  Parameters params;
  params.descriptor = routeDescriptor();
  params.sequence.sequence_length = 10;  // The route's tests were written for OpenSeqSLAM's length.
  // ... and check the answer at the test sequence's newest frame, where the evidence is one-sided.
  params.sequence.alignment = WindowAlignment::kCausal;
  return params;
}

struct DescribedRoute {
  DescriptorSequence reference{1};
  DescriptorSequence query{1};
  std::vector<int> query_to_reference;
};

inline DescribedRoute describeRoute(const SyntheticRoute& route) {
  // Frame i at i s.
  const auto frameStamp = [](std::size_t i) {
    return Stamp::fromSecondsAndNanoseconds(static_cast<std::uint32_t>(i), 0);
  };
  const DescriptorExtractor extractor{routeDescriptor()};
  DescribedRoute described;
  described.reference = DescriptorSequence(extractor.size());
  described.query = DescriptorSequence(extractor.size());
  for (std::size_t i = 0; i < route.reference.size(); ++i) {
    described.reference.append(extractor.compute(route.reference[i]), frameStamp(i));
  }
  for (std::size_t i = 0; i < route.query.size(); ++i) {
    described.query.append(extractor.compute(route.query[i]), frameStamp(i));
  }
  described.query_to_reference = route.query_to_reference;
  return described;
}

inline DescribedRoute describeRoute(const SyntheticRouteParams& route_params) {
  return describeRoute(generateSyntheticRoute(route_params));
}

/// The reference images of a route of `frames` frames, generated for a test that needs a camera's few
/// frames (its query traversal, of the fewest frames a route has, is left unused).
inline std::vector<cv::Mat> shortRouteImages(int frames) {
  SyntheticRouteParams params;
  params.reference_frames = frames;
  params.query_frames = 2;
  return generateSyntheticRoute(params).reference;
}

/// The images of the default route (SyntheticRouteParams{}: 400 reference frames, 300 query frames,
/// 128 x 64), generated once per test program.
inline const SyntheticRoute& defaultRouteImages() {
  static const SyntheticRoute route = generateSyntheticRoute(SyntheticRouteParams{});
  return route;
}

/// The default route generated with another seed: none of its places is in the default route's map.
inline const SyntheticRoute& unmappedRouteImages() {
  static const SyntheticRoute route = [] {
    SyntheticRouteParams params;
    params.seed = 8;
    return generateSyntheticRoute(params);
  }();
  return route;
}

/// The images of the standard route: 600 reference frames, 400 query frames, the default seed.
inline const SyntheticRoute& standardRouteImages() {
  static const SyntheticRoute route = [] {
    SyntheticRouteParams params;
    params.reference_frames = 600;
    params.query_frames = 400;
    return generateSyntheticRoute(params);
  }();
  return route;
}

/// The standard route described.
inline const DescribedRoute& standardRoute() {
  static const DescribedRoute route = describeRoute(standardRouteImages());
  return route;
}

/// A long reference (2400 frames) for cost comparisons; only its first 300 query frames are used.
inline const DescribedRoute& longRoute() {
  static const DescribedRoute route = [] {
    SyntheticRouteParams params;
    params.reference_frames = 2400;
    params.query_frames = 300;
    params.image_width = 64;
    params.image_height = 32;
    params.start_place = 1500.0;
    params.seed = 21;
    return describeRoute(params);
  }();
  return route;
}

/// Parameters for global queries of 100+ frames. The generated route's neighbouring frames do not
/// look alike (the difference dips over one frame only), so a trajectory whose velocity is off by
/// half a step of 0.1 drifts off the dip after ~20 frames: long sequences need a finer step, as the
/// benchmark uses (0.02: at most 2 frames of drift over 200 frames).
inline Parameters globalSearchParams() {
  Parameters params = routeParameters();
  params.sequence.velocity_step = 0.02;
  return params;
}

/// True when `predicted` is within `tolerance` frames of `truth`.
inline bool within(int predicted, int truth, int tolerance) { return std::abs(predicted - truth) <= tolerance; }

}  // namespace testing_support
}  // namespace mrs_vpr
