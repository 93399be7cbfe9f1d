#include "camera_drive_rows.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "drive_listings.hpp"
#include "mrs_vpr/evaluation/camera_drive.hpp"
#include "mrs_vpr/evaluation/evaluation.hpp"
#include "mrs_vpr/evaluation/route_places.hpp"
#include "mrs_vpr/node/continuous_queries.hpp"
#include "mrs_vpr/node/node_parameters.hpp"
#include "mrs_vpr/node/standing_frames.hpp"
#include "mrs_vpr/place_recognizer.hpp"
#include "mrs_vpr/trajectory_search.hpp"
#include "replayed_drive.hpp"

namespace mrs_vpr {
namespace benchmark {
namespace {

constexpr double kMapRate = 30.0;      // [Hz] the map drive's camera
constexpr double kRevisitRate = 10.0;  // [Hz] the revisit's camera
constexpr double kQueryPeriod = 1.0;   // [s] launch/mrs_vpr.launch's auto_query_period
/// An answer is right when the revisit frame's place is within this many places of a place the
/// answer's keyframe stands for (evaluation/route_places.hpp: route frames where the recording camera
/// stood are one place).
constexpr int kRouteTolerance = 2;
/// mrs_vpr_eval's --tolerance default [frames].
constexpr int kEvaluatorTolerance = kDefaultTolerance;

/**
 * Both drives, one after the other, into one recognizer at the node's defaults but for the front end,
 * the sequence search and the keyframe threshold given, asked every period
 * as the node's continuous mode asks: only when a keyframe came since the last question, and only once
 * the map holds 2 L + recent_exclusion keyframes.
 */
std::vector<DriveCounts> continuousMode(const std::vector<const Drive*>& drives, const std::vector<int>& route_places,
                                        const std::string& method, const DescriptorParams& descriptor,
                                        const SequenceParams& sequence, double min_appearance_change,
                                        bool each_keyframe, int* length) {
  node::NodeParameters node;
  node.core.descriptor = descriptor;
  node.core.sequence = sequence;
  node.recognizer.min_appearance_change = min_appearance_change;
  PlaceRecognizer recognizer(node.core, node.recognizer);
  const int recent = node.autoQueryFrames();
  *length = recent;
  std::vector<int> route_frame_numbers(route_places.size());  // each route frame a place of its own
  for (std::size_t i = 0; i < route_frame_numbers.size(); ++i) route_frame_numbers[i] = static_cast<int>(i);
  ReplayLog log;
  // As the node restates a closure for the frames its keyframe stands for (standing_frames.hpp).
  node::StandingFrames standing(kQueryPeriod);
  const bool show_false = std::getenv("MRS_VPR_SHOW_FALSE") != nullptr;
  const bool show_missed = std::getenv("MRS_VPR_SHOW_MISSED") != nullptr;
  double clock = 1.0;  // [s]
  std::vector<DriveCounts> counts(drives.size());
  int asked_at_size = 0;
  for (std::size_t d = 0; d < drives.size(); ++d) {
    const Drive& drive = *drives[d];
    DriveCounts& count = counts[d];
    const int period = static_cast<int>(std::lround(kQueryPeriod * drive.rate));
    const int stretches = std::max(0, (static_cast<int>(drive.frames.size()) - kWarmUpFrames) / kStretchFrames);
    count.stretch_right.assign(static_cast<std::size_t>(stretches), false);
    count.stretch_keyframed.assign(static_cast<std::size_t>(stretches), false);
    count.stretch_answers.assign(static_cast<std::size_t>(stretches), "");
    const auto stretchOf = [&](int i) { return i < kWarmUpFrames ? -1 : (i - kWarmUpFrames) / kStretchFrames; };
    const int drive_start = log.frames();  // the drive's first frame in the replay
    for (int i = 0; i < static_cast<int>(drive.frames.size()); ++i) {
      const DriveFrame& frame = drive.frames[static_cast<std::size_t>(i)];
      const int t = log.add(frame.route_frame, Stamp::fromSeconds(clock));
      clock += 1.0 / drive.rate;
      const int stretch = stretchOf(i);
      const FrameAdmission admission = recognizer.addFrame(drive.images[static_cast<std::size_t>(i)]);
      if (admission == FrameAdmission::kTooSimilar && recognizer.lastFrameStood()) {
        standing.tooSimilar(log.stamp(t));
      }
      if (admission == FrameAdmission::kAdmitted) {
        standing.keyframe(log.stamp(t));
        log.markKeyframe(t);
        ++count.keyframes;
        count.stopped_keyframes += frame.kind == DriveFrameKind::kStopped ? 1 : 0;
        if (stretch >= 0 && stretch < stretches) count.stretch_keyframed[static_cast<std::size_t>(stretch)] = true;
      }
      if ((i + 1) % period != 0) continue;
      const int size = recognizer.size();
      const int first_size = recognizer.fewestFramesForRecent(recent);
      if (size == asked_at_size || size < first_size) continue;
      // As the node asks (node/continuous_queries.hpp), with no time budget; or about the newest only.
      const std::vector<int> ends = each_keyframe
                                        ? node::continuousQueryEnds(asked_at_size, size, first_size, size)
                                        : std::vector<int>{size};
      asked_at_size = size;
      for (const int end : ends) {
        const Match match = recognizer.matchRecent(recent, method, nullptr, end).match;
        ++count.queries;
        if (match.reference_index < 0) continue;
        // The localised keyframe's place (the newest, or the middle one when centred) against the places
        // the answer's keyframe stands for; no place comes back during the first traversal.
        const int anchor = end - recent + wholeSequenceRows(recent, sequence.alignment).anchor;
        const int localised_frame = log.keyframeFrame(anchor);
        // From `frame` to the nearest frame the answer's keyframe stands for, in places or in route frames.
        const auto distance = [&](int frame, const std::vector<int>& position_of_route_frame) {
          return log.distance(frame, match.reference_index, position_of_route_frame);
        };
        // Right: within kRouteTolerance of a frame the answer's keyframe stands for, on a revisit.
        const auto within = [&](int frame, const std::vector<int>& position_of_route_frame) {
          return d > 0 && distance(frame, position_of_route_frame) <= kRouteTolerance;
        };
        const auto answerShows = [&](int frame) { return within(frame, route_places); };
        const auto noteWrong = [&](int frame) {
          if (d == 0) return;  // No place comes back on the first traversal: every closure there is wrong.
          count.largest_wrong_places = std::max(count.largest_wrong_places, distance(frame, route_places));
          count.largest_wrong_route_frames =
              std::max(count.largest_wrong_route_frames, distance(frame, route_frame_numbers));
        };
        const bool right = answerShows(localised_frame);
        const int localised_stretch = stretchOf(localised_frame - drive_start);
        if (show_missed && localised_stretch >= 0 && localised_stretch < stretches) {
          count.stretch_answers[static_cast<std::size_t>(localised_stretch)] +=
              answerNote(log.routeFrame(localised_frame), match, right);
        }
        if (!match.accepted) continue;
        ++count.accepted;
        ++(right ? count.right : count.wrong);
        if (!right) noteWrong(localised_frame);
        if (!within(localised_frame, route_frame_numbers)) ++count.wrong_route_frames;
        if (!right && show_false) {
          printFalseClosure(method, drive.name, i, log, match, end, recent, anchor);
        }
        // A closure belongs to the stretch of the frame it localises (its header stamp in the node).
        const auto confirm = [&](int frame) {
          const int stretch = stretchOf(frame - drive_start);
          if (stretch >= 0 && stretch < stretches) count.stretch_right[static_cast<std::size_t>(stretch)] = true;
        };
        if (right) confirm(localised_frame);
        // The same closure restated for the stopped frames the localised keyframe stands for.
        for (const Stamp stood : standing.of(log.stamp(localised_frame))) {
          const int frame = log.frameAt(stood);
          const bool stood_right = answerShows(frame);
          ++(stood_right ? count.standing_right : count.standing_wrong);
          if (stood_right) confirm(frame);
          if (!stood_right) noteWrong(frame);
        }
      }
    }
    if (show_missed && d > 0) printMissedStretches(*drives.front(), drive, count);
  }
  return counts;
}

/// The evaluator's per-frame protocol on two drives, as mrs_vpr_eval runs it on make_drive's folders
/// with make_drive's ground truth (--places-from both seasons): both keyframed as the node keyframes a
/// camera, every query keyframe with a full sequence searched, an answer right when the truth is among
/// the frames its keyframe stands for (within the evaluator's tolerance).
EvaluationSummary perFrameProtocol(const Drive& reference_drive, const Drive& query_drive,
                                   const std::vector<int>& route_places, const std::string& method,
                                   const DescriptorParams& descriptor, const SequenceParams& sequence,
                                   double min_appearance_change, int* reference_keyframes) {
  Parameters params;
  params.descriptor = descriptor;
  params.sequence = sequence;
  RecognizerParams map_params;
  map_params.max_frames = 0;
  map_params.min_appearance_change = min_appearance_change;
  PlaceRecognizer reference(params, map_params);
  Keyframes reference_keyframed;
  for (const cv::Mat& image : reference_drive.images) {
    const int frame = reference_keyframed.total++;
    if (reference.offerDescriptor(reference.describe(image)) == FrameAdmission::kAdmitted) {
      reference_keyframed.frames.push_back(frame);
    }
  }
  *reference_keyframes = reference.size();
  // The revisit is keyframed as the evaluator keyframes it: on the map's scale (keyframesOf).
  DescriptorSequence revisit(reference.extractor().size());
  for (const cv::Mat& image : query_drive.images) revisit.append(reference.describe(image));
  Keyframes query_keyframed;
  query_keyframed.total = static_cast<int>(query_drive.images.size());
  const DescriptorSequence query = reference.keyframesOf(revisit, &query_keyframed.frames);
  const GroundTruth truth =
      driveGroundTruth(placesOf(routeFramesOf(reference_drive.frames), route_places),
                       placesOf(routeFramesOf(query_drive.frames), route_places), kRouteTolerance);
  const std::vector<int> searched = perFrameQueries(query.size(), params.sequence);
  const auto start = std::chrono::steady_clock::now();
  const std::vector<Match> matches = reference.matchEveryFrame(query.view(), method);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() /
                    std::max<std::size_t>(searched.size(), 1);
  std::vector<QueryRecord> records;
  for (const int keyframe : searched) {
    const int frame = query_keyframed.frames[static_cast<std::size_t>(keyframe)];
    records.push_back(keyframeRecordOf(frame, truth.at(frame), matches.at(static_cast<std::size_t>(keyframe)),
                                       reference_keyframed, ms));
  }
  return summarise(records, kEvaluatorTolerance);
}

double shareOf(const std::vector<bool>& flags) {
  if (flags.empty()) return std::nan("");
  return static_cast<double>(std::count(flags.begin(), flags.end(), true)) / static_cast<double>(flags.size());
}

}  // namespace

void runCameraDrives(const CameraDriveInput& input, const std::function<void(const std::vector<nlohmann::json>&)>& add,
                     const PerFrameRow& per_frame) {
  if (input.summer == nullptr || input.winter == nullptr)
    throw std::invalid_argument("camera drives need both seasons");
  const int route = input.route_frames;
  const Drive map = makeDrive("map drive, summer 0.." + std::to_string(route - 1), kMapRate, *input.summer, 0, route,
                              input.seed);
  const std::vector<cv::Mat> summer_route(input.summer->begin(), input.summer->begin() + route);
  const std::vector<cv::Mat> winter_route(input.winter->begin(), input.winter->begin() + route);
  const std::vector<int> places = routePlaces({&summer_route, &winter_route});
  const Drive revisit = makeDrive("revisit, winter " + std::to_string(input.part_begin) + ".." +
                                      std::to_string(input.part_end - 1),
                                  kRevisitRate, *input.winter, input.part_begin, input.part_end, input.seed + 1);

  std::printf("\nCamera drives (make_drive --seed %llu and %llu): the map drive at %.0f Hz, the revisit at %.0f Hz, "
              "each with 8 stops of 30-90 frames (noise, vibration, gain, a passer-by) and a stretch at half and one "
              "at double speed; one recognizer at the node's defaults (keyframes by appearance change %.2f, accepted "
              "at confidence %.1f), "
              "continuous mode every %.0f s. right = the localised keyframe's place within %d places of those the "
              "answer's keyframe stands for, where route frames at which the recorded train stood are one place "
              "(%d places in %d route frames; evaluation/route_places.hpp); wrong: by places, and in brackets were "
              "each route frame a place; stretches = %d-frame stretches of a drive after its first %d frames "
              "with an accepted right answer, restated ones included (in brackets: those in which a keyframe came, the "
              "others lie within a stop); restated = accepted closures restated for the stopped frames their "
              "keyframe stands for, one a period (node/standing_frames.hpp), right/wrong alike\n",
              static_cast<unsigned long long>(input.seed), static_cast<unsigned long long>(input.seed + 1), kMapRate,
              kRevisitRate, input.min_appearance_change, input.sequence.accept_threshold, kQueryPeriod, kRouteTolerance,
              places.back() + 1, route, kStretchFrames, kWarmUpFrames);
  for (const Drive* drive : {&map, &revisit}) {
    std::printf("  %-26s %5zu frames, %4d stopped; %d route frames at half speed from %d, %d at double speed from %d\n",
                drive->name.c_str(), drive->frames.size(), stoppedFrames(*drive), drive->slow_frames, drive->slow_begin,
                drive->fast_frames, drive->fast_begin);
  }
  std::printf("%-28s %-8s %4s %9s %10s %7s %8s %5s %10s %17s\n", "drive", "method", "L", "keyframes", "kf stopped",
              "queries", "accepted", "right", "wrong", "stretches");
  std::vector<nlohmann::json> rows;
  for (const std::string& method : input.methods) {
    int length = 0;
    const std::vector<DriveCounts> counts =
        continuousMode({&map, &revisit}, places, method, input.descriptor, input.sequence,
                       input.min_appearance_change, input.each_keyframe, &length);
    for (std::size_t d = 0; d < counts.size(); ++d) {
      const Drive& drive = d == 0 ? map : revisit;
      const DriveCounts& c = counts[d];
      const int stretches = static_cast<int>(c.stretch_right.size());
      const int with_right = static_cast<int>(std::count(c.stretch_right.begin(), c.stretch_right.end(), true));
      const int keyframed = static_cast<int>(std::count(c.stretch_keyframed.begin(), c.stretch_keyframed.end(), true));
      const std::string wrong = std::to_string(c.wrong) + " (" + std::to_string(c.wrong_route_frames) + ")";
      std::printf("%-28s %-8s %4d %9d %10d %7d %8d %5d %10s %4d/%-4d (%d) %.3f  restated %d/%d", drive.name.c_str(),
                  method.c_str(), length, c.keyframes, c.stopped_keyframes, c.queries, c.accepted, c.right,
                  wrong.c_str(), with_right, stretches, keyframed, shareOf(c.stretch_right), c.standing_right,
                  c.standing_wrong);
      if (d > 0 && c.wrong + c.standing_wrong > 0) {
        std::printf(", wrong by up to %d places (%d route frames)", c.largest_wrong_places,
                    c.largest_wrong_route_frames);
      }
      std::printf("\n");
      const double share = shareOf(c.stretch_right);
      rows.push_back({{"setting", "camera drive continuous " + std::string(d == 0 ? "map drive" : "revisit")},
                      {"method", method},
                      {"protocol", "continuous"},
                      {"out_of_map", d == 0},
                      {"drive",
                       {{"frames", drive.frames.size()},
                        {"stopped_frames", stoppedFrames(drive)},
                        {"rate_hz", drive.rate},
                        {"route_begin", drive.frames.front().route_frame},
                        {"route_end", drive.frames.back().route_frame + 1}}},
                      {"sequence_length", length},
                      {"query_period_s", kQueryPeriod},
                      {"keyframes", c.keyframes},
                      {"stopped_keyframes", c.stopped_keyframes},
                      {"queries", c.queries},
                      {"accepted", c.accepted},
                      {"accepted_right", c.right},
                      {"accepted_wrong", c.wrong},
                      {"accepted_wrong_by_route_frame", c.wrong_route_frames},
                      {"restated_right", c.standing_right},
                      {"restated_wrong", c.standing_wrong},
                      {"largest_wrong_error_places", c.largest_wrong_places},
                      {"largest_wrong_error_route_frames", c.largest_wrong_route_frames},
                      {"stretches", stretches},
                      {"stretches_keyframed", keyframed},
                      {"stretches_with_right", with_right},
                      {"stretch_share", std::isfinite(share) ? nlohmann::json(share) : nlohmann::json()}});
    }
  }
  add(rows);
  std::printf("\n");
  for (const std::string& method : input.methods) {
    int reference_keyframes = 0;
    const EvaluationSummary summary =
        perFrameProtocol(map, revisit, places, method, input.descriptor, input.sequence, input.min_appearance_change,
                         &reference_keyframes);
    per_frame("camera drives per-frame (mrs_vpr_eval)", method, summary, reference_keyframes,
              input.sequence.sequence_length);
  }
}

}  // namespace benchmark
}  // namespace mrs_vpr
