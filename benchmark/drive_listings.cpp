#include "drive_listings.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <vector>

namespace mrs_vpr {
namespace benchmark {
namespace {

/// Frames of `frames` whose route frame lies in [begin, begin + count): those of a stretch driven at
/// another speed.
long framesWithin(const std::vector<DriveFrame>& frames, int begin, int count) {
  return static_cast<long>(std::count_if(frames.begin(), frames.end(), [&](const DriveFrame& frame) {
    return begin >= 0 && frame.route_frame >= begin && frame.route_frame < begin + count;
  }));
}

}  // namespace

std::string answerNote(int route_frame, const Match& match, bool right) {
  char note[64];
  std::snprintf(note, sizeof note, " %d:%.1f%s%s%s%s", route_frame, match.confidence, match.accepted ? "A" : "",
                right ? "" : "x", match.at_velocity_bound ? "b" : "", match.repeated_view ? "r" : "");
  return note;
}

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

void printFalseClosure(const std::string& method, const std::string& drive, int drive_frame, const ReplayLog& log,
                       const Match& match, int end, int recent, int anchor) {
  const auto [first, last] = log.framesOf(match.reference_index);
  std::fprintf(stderr,
               "false closure: %s %s frame %d, localised keyframe at route frame %d -> keyframe %d, route "
               "frames %d..%d, confidence %.2f, velocity %.2f\n",
               method.c_str(), drive.c_str(), drive_frame, log.routeOfKeyframe(anchor), match.reference_index,
               log.routeFrame(first), log.routeFrame(last), match.confidence, match.velocity);
  std::fprintf(stderr, "  test keyframes:");
  for (int q = end - recent; q < end; ++q)
    std::fprintf(stderr, " %d%s", log.routeOfKeyframe(q), q == anchor ? "*" : "");
  std::fprintf(stderr, "\n  map keyframes: ");
  const int shown_end = std::min(log.keyframes(), match.reference_index + recent);
  for (int q = std::max(0, match.reference_index - recent); q < shown_end; ++q) {
    std::fprintf(stderr, " %d%s", log.routeOfKeyframe(q), q == match.reference_index ? "*" : "");
  }
  std::fprintf(stderr, "\n");
}

}  // namespace benchmark
}  // namespace mrs_vpr
