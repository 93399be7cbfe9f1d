#include "mrs_vpr/node/keyframe_policy.hpp"

#include <algorithm>

namespace mrs_vpr {
namespace node {
namespace {

constexpr double kJitterTolerance = 0.1;  // of min_frame_interval

}  // namespace

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
  if (steppedBackFrom(stamp)) {
    return true;
  }
  // Early by less than half a frame period, this frame is nearer the interval than the next one will
  // be; the slack is capped so that keyframes stay at least 90% of the interval apart.
  const double frame_period = has_frame_ ? std::max(0.0, stamp - last_frame_stamp_) : 0.0;
  const double slack = std::min(0.5 * frame_period, kJitterTolerance * min_frame_interval_);
  return stamp - last_stamp_ >= min_frame_interval_ - slack;
}

void KeyframePolicy::skip(double stamp) {
  ++frames_since_keyframe_;
  has_frame_ = true;
  last_frame_stamp_ = stamp;
}

std::optional<double> KeyframePolicy::steppedBackFrom(double stamp) const {
  if (has_keyframe_ && stamp < last_stamp_) return last_stamp_;
  return std::nullopt;
}

void KeyframePolicy::keep(double stamp) {
  has_keyframe_ = true;
  last_stamp_ = stamp;
  has_frame_ = true;
  last_frame_stamp_ = stamp;
  frames_since_keyframe_ = 0;
}

void KeyframePolicy::reset() {
  has_keyframe_ = false;
  last_stamp_ = 0.0;
  has_frame_ = false;
  last_frame_stamp_ = 0.0;
  frames_since_keyframe_ = 0;
}

}  // namespace node
}  // namespace mrs_vpr
