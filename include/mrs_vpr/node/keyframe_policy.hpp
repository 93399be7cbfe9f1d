#pragma once

#include <cstdint>
#include <optional>

namespace mrs_vpr {
namespace node {

/**
 * Decides which camera frames become reference keyframes: a frame is kept when at least
 * `frame_stride` frames have arrived since the last keyframe and its stamp is `min_frame_interval`
 * seconds after the last keyframe's, less a slack for stamp jitter: half a camera frame period (the
 * time between the two newest frames), at most a tenth of the interval. So the frame nearest the
 * interval is kept rather than the first one after it: with jittered stamps of a camera as slow as the
 * interval (1 Hz, interval 1 s), a frame 0.98 s after the keyframe is kept, not the next one 2 s after
 * it, and a 30 Hz camera gives keyframes 1 s apart on average, not 1 s plus a frame. A stamp earlier than
 * the last keyframe's (a bag replayed from its start, a simulated clock reset) restarts the interval.
 * No ROS inside.
 */
class KeyframePolicy {
 public:
  KeyframePolicy(double min_frame_interval, int frame_stride);

  /// True when the frame stamped `stamp` (seconds) should be kept. Does not remember it: call keep()
  /// once the frame has really been added, or skip() otherwise, so a frame that fails later does not
  /// count as a keyframe.
  bool wants(double stamp) const;
  /// Records a frame that was not kept (counts toward the stride and the frame period).
  void skip(double stamp);
  /// Records a keyframe.
  void keep(double stamp);
  /// The last keyframe's stamp when `stamp` comes before it (a bag played again, a clock reset); else
  /// nullopt.
  std::optional<double> steppedBackFrom(double stamp) const;
  /// Forgets the last keyframe (after the map is reset).
  void reset();

 private:
  double min_frame_interval_;
  int frame_stride_;
  bool has_keyframe_ = false;
  double last_stamp_ = 0.0;        // of the last keyframe
  bool has_frame_ = false;
  double last_frame_stamp_ = 0.0;  // of the last frame, kept or not
  std::int64_t frames_since_keyframe_ = 0;
};

}  // namespace node
}  // namespace mrs_vpr
