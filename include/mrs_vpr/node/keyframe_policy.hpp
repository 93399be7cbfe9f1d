#pragma once

#include <cstdint>

namespace mrs_vpr {
namespace node {

/**
 * Decides which camera frames become reference keyframes: a frame is kept when at least
 * `frame_stride` frames have arrived since the last keyframe and its stamp is at least
 * `min_frame_interval` seconds after the last keyframe's. A stamp earlier than the last keyframe's
 * (a bag replayed from its start, a simulated clock reset) restarts the interval. No ROS inside.
 */
class KeyframePolicy {
 public:
  KeyframePolicy(double min_frame_interval, int frame_stride);

  /// True when the frame stamped `stamp` (seconds) should be kept. Does not remember it: call
  /// keep() once the frame has really been added, so a frame that fails later does not count.
  bool wants(double stamp) const;
  /// Records a frame that was not kept (counts toward the stride).
  void skip();
  /// Records a keyframe.
  void keep(double stamp);
  /// Forgets the last keyframe (after the map is reset).
  void reset();

 private:
  double min_frame_interval_;
  int frame_stride_;
  bool has_keyframe_ = false;
  double last_stamp_ = 0.0;
  std::int64_t frames_since_keyframe_ = 0;
};

}  // namespace node
}  // namespace mrs_vpr
