#include "mrs_vpr/node/keyframe_policy.hpp"

namespace mrs_vpr {
namespace node {

KeyframePolicy::KeyframePolicy(double min_frame_interval, int frame_stride)
    : min_frame_interval_(min_frame_interval), frame_stride_(frame_stride) {}

bool KeyframePolicy::wants(double stamp) const {
  if (!has_keyframe_) {
    return true;
  }
  if (frames_since_keyframe_ + 1 < frame_stride_) {
    return false;
  }
  // Time running backwards means a new recording or a clock reset, not a robot that stands still.
  return stamp < last_stamp_ || stamp - last_stamp_ >= min_frame_interval_;
}

void KeyframePolicy::skip() { ++frames_since_keyframe_; }

void KeyframePolicy::keep(double stamp) {
  has_keyframe_ = true;
  last_stamp_ = stamp;
  frames_since_keyframe_ = 0;
}

void KeyframePolicy::reset() {
  has_keyframe_ = false;
  last_stamp_ = 0.0;
  frames_since_keyframe_ = 0;
}

}  // namespace node
}  // namespace mrs_vpr
