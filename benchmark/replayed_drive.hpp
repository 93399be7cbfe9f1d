#pragma once

// A drive of real frames as the camera-drive rows replay it (make_drive's plan rendered on a season's
// frames), what one method did on it in continuous mode, and the log of the replay.

#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

#include "mrs_vpr/evaluation/camera_drive.hpp"
#include "mrs_vpr/stamp.hpp"

namespace mrs_vpr {
namespace benchmark {

/// A revisit's share of stretches is counted after the revisit's first frames (the map must reach back).
constexpr int kWarmUpFrames = 100;
constexpr int kStretchFrames = 20;

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

/// The drive of `season`'s route frames [begin, end) at `rate` [Hz], with make_drive's defaults and `seed`;
/// its stretches at half and double speed are each at most a quarter of the route.
Drive makeDrive(const std::string& name, double rate, const std::vector<cv::Mat>& season, int begin, int end,
                std::uint64_t seed);

/// How many of the drive's frames stood.
int stoppedFrames(const Drive& drive);

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
  int distance(int frame, int keyframe, const std::vector<int>& position_of_route_frame) const;

 private:
  std::vector<int> route_of_frame_;
  std::vector<Stamp> stamp_of_frame_;
  std::vector<int> keyframe_frame_;
};

}  // namespace benchmark
}  // namespace mrs_vpr
