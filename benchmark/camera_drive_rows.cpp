#include "camera_drive_rows.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "mrs_vpr/evaluation/camera_drive.hpp"
#include "mrs_vpr/evaluation/route_places.hpp"
#include "mrs_vpr/node/continuous_queries.hpp"
#include "mrs_vpr/node/node_parameters.hpp"
#include "mrs_vpr/node/standing_frames.hpp"
#include "mrs_vpr/place_recognizer.hpp"
#include "mrs_vpr/trajectory_search.hpp"

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
/// The share of stretches is counted after the revisit's first frames (the map must reach back).
constexpr int kWarmUpFrames = 100;
constexpr int kStretchFrames = 20;
/// mrs_vpr_eval's --tolerance default [frames].
constexpr int kEvaluatorTolerance = 2;

/// A drive of real frames: its images and the route frame and kind of each.
struct Drive {
  std::string name;
  double rate = 0.0;
  std::vector<cv::Mat> images;
  std::vector<DriveFrame> frames;  ///< route_frame numbered as the season's frames.
  int slow_frames = 0;
  int slow_begin = -1;
  int fast_frames = 0;
  int fast_begin = -1;
};

Drive makeDrive(const std::string& name, double rate, const std::vector<cv::Mat>& season, int begin, int end,
                std::uint64_t seed) {
  CameraDriveSettings settings;
  settings.seed = seed;
  // A short route (a test's) keeps room for the stops beside the stretches.
  settings.slow_frames = std::min(settings.slow_frames, (end - begin) / 4);
  settings.fast_frames = std::min(settings.fast_frames, (end - begin) / 4);
  const CameraDrive plan(end - begin, settings);
  const std::vector<cv::Mat> route(season.begin() + begin, season.begin() + end);
  Drive drive{name,
              rate,
              renderDrive(plan, route),
              plan.frames(),
              settings.slow_frames,
              plan.slowBegin() < 0 ? -1 : begin + plan.slowBegin(),
              settings.fast_frames,
              plan.fastBegin() < 0 ? -1 : begin + plan.fastBegin()};
  for (DriveFrame& frame : drive.frames) frame.route_frame += begin;
  return drive;
}

int stoppedFrames(const Drive& drive) {
  return static_cast<int>(std::count_if(drive.frames.begin(), drive.frames.end(),
                                        [](const DriveFrame& f) { return f.kind == DriveFrameKind::kStopped; }));
}

/// What one method did on one drive in continuous mode.
struct DriveCounts {
  int keyframes = 0;
  int stopped_keyframes = 0;  ///< Keyframes among the stopped frames.
  int queries = 0;
  int accepted = 0;
  int right = 0;
  int wrong = 0;
  int wrong_route_frames = 0;  ///< Accepted answers wrong were each route frame a place of its own.
  int standing_right = 0;  ///< Closures restated for the stopped frames a localised keyframe stands for.
  int standing_wrong = 0;
  /// The farthest a wrong closure (accepted or restated) lies from what its answer's keyframe stands
  /// for: how wrong the wrong ones are (0 when there are none). In places (the judge's unit: route
  /// frames where the recording stood count as one) and in route frames.
  int largest_wrong_places = 0;
  int largest_wrong_route_frames = 0;
  std::vector<bool> stretch_right;       ///< Per 20-frame stretch after the warm-up: an accepted right answer.
  std::vector<bool> stretch_keyframed;   ///< ... and whether a keyframe came in it (else no question is asked).
  std::vector<std::string> stretch_answers;  ///< MRS_VPR_SHOW_MISSED: answerNote() of each answer about it.
};

/// One answer as MRS_VPR_SHOW_MISSED lists it: the localised route frame, the confidence, and A
/// (accepted), x (wrong), b (at a velocity bound) or r (repeated view).
std::string answerNote(int route_frame, const Match& match, bool right) {
  char note[64];
  std::snprintf(note, sizeof note, " %d:%.1f%s%s%s%s", route_frame, match.confidence, match.accepted ? "A" : "",
                right ? "" : "x", match.at_velocity_bound ? "b" : "", match.repeated_view ? "r" : "");
  return note;
}

/// Frames of `frames` whose route frame lies in [begin, begin + count): those of a stretch driven at
/// another speed.
long framesWithin(const std::vector<DriveFrame>& frames, int begin, int count) {
  return static_cast<long>(std::count_if(frames.begin(), frames.end(), [&](const DriveFrame& frame) {
    return begin >= 0 && frame.route_frame >= begin && frame.route_frame < begin + count;
  }));
}

/// MRS_VPR_SHOW_MISSED: each stretch of the revisit that no accepted right answer confirmed, with its
/// route frames; how many of its frames stood, were half-speed copies, were driven at double speed,
/// or show route frames that the map drive drove at double or half speed; whether a keyframe came; and
/// the answers about its keyframes. Stretches without a keyframe are confirmed only by a closure
/// restated for their stop (standing_frames.hpp).
void printMissedStretches(const Drive& map, const Drive& revisit, const DriveCounts& count) {
  for (std::size_t stretch = 0; stretch < count.stretch_right.size(); ++stretch) {
    if (count.stretch_right[stretch]) continue;
    const auto first = revisit.frames.begin() + static_cast<std::ptrdiff_t>(kWarmUpFrames + stretch * kStretchFrames);
    const std::vector<DriveFrame> frames(first, first + kStretchFrames);
    const auto kindCount = [&](DriveFrameKind kind) {
      return static_cast<long>(std::count_if(frames.begin(), frames.end(),
                                             [&](const DriveFrame& frame) { return frame.kind == kind; }));
    };
    std::fprintf(stderr,
                 "missed stretch: %s route frames %d..%d, stopped %ld, slow %ld, fast %ld, map fast %ld, map slow "
                 "%ld, keyframed %d, answers:%s\n",
                 revisit.name.c_str(), frames.front().route_frame, frames.back().route_frame,
                 kindCount(DriveFrameKind::kStopped), kindCount(DriveFrameKind::kSlowCopy),
                 framesWithin(frames, revisit.fast_begin, revisit.fast_frames),
                 framesWithin(frames, map.fast_begin, map.fast_frames),
                 framesWithin(frames, map.slow_begin, map.slow_frames), count.stretch_keyframed[stretch] ? 1 : 0,
                 count.stretch_answers[stretch].c_str());
  }
}

/// The replay so far: the route frame and stamp of every frame of both drives, one after the other,
/// and which of them became keyframes.
class ReplayLog {
 public:
  /// Records the next frame; returns its index in the replay.
  int add(int route_frame, Stamp stamp) {
    route_of_frame_.push_back(route_frame);
    stamp_of_frame_.push_back(stamp);
    return frames() - 1;
  }
  void markKeyframe(int frame) { keyframe_frame_.push_back(frame); }

  int frames() const { return static_cast<int>(route_of_frame_.size()); }
  int routeFrame(int frame) const { return route_of_frame_.at(static_cast<std::size_t>(frame)); }
  Stamp stamp(int frame) const { return stamp_of_frame_.at(static_cast<std::size_t>(frame)); }
  /// The first frame stamped `stamp` or later.
  int frameAt(Stamp stamp) const {
    return static_cast<int>(std::lower_bound(stamp_of_frame_.begin(), stamp_of_frame_.end(), stamp) -
                            stamp_of_frame_.begin());
  }
  int keyframes() const { return static_cast<int>(keyframe_frame_.size()); }
  int keyframeFrame(int keyframe) const { return keyframe_frame_.at(static_cast<std::size_t>(keyframe)); }
  int routeOfKeyframe(int keyframe) const { return routeFrame(keyframeFrame(keyframe)); }

  /// The frames keyframe `keyframe` stands for: itself and those after it up to the next keyframe
  /// (or the newest frame).
  std::pair<int, int> framesOf(int keyframe) const {
    const auto next = static_cast<std::size_t>(keyframe) + 1;
    return {keyframeFrame(keyframe), (next < keyframe_frame_.size() ? keyframe_frame_[next] : frames()) - 1};
  }

  /// From `frame` to the nearest frame `keyframe` stands for, in the positions that
  /// `position_of_route_frame` gives route frames (places, or the route frames themselves).
  int distance(int frame, int keyframe, const std::vector<int>& position_of_route_frame) const {
    const int position = position_of_route_frame.at(static_cast<std::size_t>(routeFrame(frame)));
    const auto [first, last] = framesOf(keyframe);
    int off = std::numeric_limits<int>::max();
    for (int f = first; f <= last; ++f) {
      off = std::min(off, std::abs(position_of_route_frame.at(static_cast<std::size_t>(routeFrame(f))) - position));
    }
    return off;
  }

 private:
  std::vector<int> route_of_frame_;
  std::vector<Stamp> stamp_of_frame_;
  std::vector<int> keyframe_frame_;
};

/// MRS_VPR_SHOW_FALSE: a wrong closure, with the route frames of the test sequence's keyframes (* the
/// localised one) and of the map's keyframes around the answer (* the answer): where their spacing
/// differs, and how. The test sequence is keyframes [end - recent, end); `drive_frame` is the drive's
/// frame at which it was asked.
void printFalseClosure(const std::string& method, const std::string& drive, int drive_frame, const ReplayLog& log,
                       const Match& match, int end, int recent, int anchor) {
  const auto [first, last] = log.framesOf(match.reference_index);
  std::fprintf(stderr,
               "false closure: %s %s frame %d, localised keyframe at route frame %d -> keyframe %d, route "
               "frames %d..%d, confidence %.2f, velocity %.2f\n",
               method.c_str(), drive.c_str(), drive_frame, log.routeOfKeyframe(anchor), match.reference_index,
               log.routeFrame(first), log.routeFrame(last), match.confidence, match.velocity);
  std::fprintf(stderr, "  test keyframes:");
  for (int q = end - recent; q < end; ++q) std::fprintf(stderr, " %d%s", log.routeOfKeyframe(q), q == anchor ? "*" : "");
  std::fprintf(stderr, "\n  map keyframes: ");
  const int shown_end = std::min(log.keyframes(), match.reference_index + recent);
  for (int q = std::max(0, match.reference_index - recent); q < shown_end; ++q) {
    std::fprintf(stderr, " %d%s", log.routeOfKeyframe(q), q == match.reference_index ? "*" : "");
  }
  std::fprintf(stderr, "\n");
}

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
      const int first_size = 2 * recent + node.recognizer.recent_exclusion;
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
  if (input.summer == nullptr || input.winter == nullptr) throw std::invalid_argument("camera drives need both seasons");
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
      std::printf("%-28s %-8s %4d %9d %10d %7d %8d %5d %10s %4d/%-4d (%d) %.3f  restated %d/%d", drive.name.c_str(), method.c_str(),
                  length, c.keyframes, c.stopped_keyframes, c.queries, c.accepted, c.right, wrong.c_str(), with_right,
                  stretches, keyframed, shareOf(c.stretch_right), c.standing_right, c.standing_wrong);
      if (d > 0 && c.wrong + c.standing_wrong > 0) {
        std::printf(", wrong by up to %d places (%d route frames)", c.largest_wrong_places, c.largest_wrong_route_frames);
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

void printDriveSeedSummary(const std::vector<nlohmann::json>& continuous_rows) {
  // The target for a revisit: accepted right closures in this share of its stretches.
  constexpr double kStretchTarget = 0.7;
  struct Totals {
    int revisits = 0;
    int wrong = 0;
    int wrong_route_frames = 0;
    int restated_wrong = 0;
    int largest_wrong_places = 0;  ///< Over the revisits.
    int largest_wrong_route_frames = 0;
    int accepted = 0;
    double share_sum = 0.0;
    int reaching_target = 0;
    int without_wrong = 0;
    int map_accepted = 0;
    int map_queries = 0;
  };
  std::map<std::string, Totals> by_method;
  for (const nlohmann::json& row : continuous_rows) {
    Totals& totals = by_method[row.at("method").get<std::string>()];
    if (row.at("out_of_map").get<bool>()) {
      totals.map_accepted += row.at("accepted").get<int>();
      totals.map_queries += row.at("queries").get<int>();
      continue;
    }
    ++totals.revisits;
    const int wrong = row.at("accepted_wrong").get<int>();
    const int restated_wrong = row.at("restated_wrong").get<int>();
    totals.wrong += wrong;
    totals.wrong_route_frames += row.at("accepted_wrong_by_route_frame").get<int>();
    totals.restated_wrong += restated_wrong;
    totals.largest_wrong_places = std::max(totals.largest_wrong_places, row.at("largest_wrong_error_places").get<int>());
    totals.largest_wrong_route_frames =
        std::max(totals.largest_wrong_route_frames, row.at("largest_wrong_error_route_frames").get<int>());
    totals.accepted += row.at("accepted").get<int>();
    const double share = row.at("stretch_share").is_null() ? 0.0 : row.at("stretch_share").get<double>();
    totals.share_sum += share;
    totals.reaching_target += share >= kStretchTarget ? 1 : 0;
    totals.without_wrong += wrong + restated_wrong == 0 ? 1 : 0;
  }
  for (const auto& [method, t] : by_method) {
    std::printf("drives of %d seeds, %s: revisits accepted %d, wrong %d (by route frame %d), restated wrong %d, "
                "wrong by up to %d places (%d route frames); "
                "stretches confirmed %.3f on average, %d of %d revisits at %.0f%% or more, %d without a wrong "
                "closure; map drives accepted %d of %d answers\n",
                t.revisits, method.c_str(), t.accepted, t.wrong, t.wrong_route_frames, t.restated_wrong,
                t.largest_wrong_places, t.largest_wrong_route_frames,
                t.revisits > 0 ? t.share_sum / t.revisits : std::nan(""), t.reaching_target, t.revisits,
                100.0 * kStretchTarget, t.without_wrong, t.map_accepted, t.map_queries);
  }
}

}  // namespace benchmark
}  // namespace mrs_vpr
