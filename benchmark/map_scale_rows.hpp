#pragma once

// The map-scale benchmark's rows on one loaded map: queries of N frames, continuous mode's CPU share,
// questions about the map's newest frames, and how fast the machine streams the map.

#include <vector>

#include <opencv2/core.hpp>

#include "mrs_vpr/parameters.hpp"
#include "mrs_vpr/place_recognizer.hpp"
#include "map_scale_options.hpp"

namespace mrs_vpr {
namespace benchmark {

/// Route frames between continuous mode's keyframes and the recent rows'.
constexpr int kRouteGap = 100;

/// The parameters of a query of `length` frames: the core's defaults (the node's), with the velocity
/// step of mrs_vpr_real_benchmark for sequences long enough to drift (0.1 leaves up to 15 frames of
/// drift at N = 300).
mrs_vpr::Parameters paramsFor(int length, const mrs_vpr::DescriptorParams& descriptor);

/// One map's rows for test sequences of `length` frames.
void measureLength(const MapScaleOptions& options, mrs_vpr::PlaceRecognizer& recognizer, int length, double load_s,
                   double rss_per_frame, double peak_per_frame, const std::vector<cv::Mat>& winter,
                   const std::vector<cv::Mat>& summer);

/// Continuous mode: keyframes of the route in winter join the map, keyframes_per_period between two
/// periods, and each period asks as the node's timer does (node/continuous_queries.hpp): a sequence of
/// the default length (sequence/sequence_length) ending at each new keyframe, within a fifth of the
/// period by the last question's time. Prints the questions' CPU time per 1 s period and how many of
/// the keyframes were localised, for both methods.
void measureContinuous(const MapScaleOptions& options, mrs_vpr::PlaceRecognizer& recognizer,
                       const std::vector<cv::Mat>& winter);

/// Frames of the route measureRecent adds for test sequences of `length` frames.
int recentRouteFrames(const MapScaleOptions& options, int length);

/// Service questions about the map's newest frames (`~query {recent_frames: N}`, matchRecent): frames
/// of the route in winter join the map as keyframes, from `next_route_frame` on, and both methods
/// answer on the same map. Three kinds of row: "recent" asks after each new keyframe, as while
/// continuous mode runs, so that MRS has kept the rows of all but the newest frame
/// (mrs/recent_rows.hpp); "recent=" asks again with no new keyframe, as of a loaded map that is not
/// growing, so that MRS has every row; "recent*" asks after N new keyframes, none of whose rows it
/// has, so that it searches as for any test sequence.
void measureRecent(const MapScaleOptions& options, mrs_vpr::PlaceRecognizer& recognizer, int length, double load_s,
                   double rss_per_frame, double peak_per_frame, const std::vector<cv::Mat>& winter,
                   int& next_route_frame);

/// How fast this machine streams the map: the differences of one keyframe to every map frame, which is
/// what a question with rows kept computes anew (the new keyframe's row). It reads every descriptor
/// once for one comparison each, so memory bandwidth, not arithmetic, sets its time; the brute force
/// makes N comparisons a descriptor read. The ratio of the two therefore differs from machine to
/// machine: the line tells what the "recent" rows' speed-up is made of here. On a copy of the map's
/// first `frames` frames (the map as loaded), taken after every other row, so that no other figure
/// includes it.
void measureMapStream(const mrs_vpr::PlaceRecognizer& recognizer, int frames);

}  // namespace benchmark
}  // namespace mrs_vpr
