#include "replayed_drive.hpp"

#include <algorithm>
#include <cstdlib>
#include <limits>

namespace mrs_vpr {
namespace benchmark {

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

int ReplayLog::distance(int frame, int keyframe, const std::vector<int>& position_of_route_frame) const {
  const int position = position_of_route_frame.at(static_cast<std::size_t>(routeFrame(frame)));
  const auto [first, last] = framesOf(keyframe);
  int off = std::numeric_limits<int>::max();
  for (int f = first; f <= last; ++f) {
    off = std::min(off, std::abs(position_of_route_frame.at(static_cast<std::size_t>(routeFrame(f))) - position));
  }
  return off;
}

}  // namespace benchmark
}  // namespace mrs_vpr
