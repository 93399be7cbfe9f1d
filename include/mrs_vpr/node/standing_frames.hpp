#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <vector>

#include "mrs_vpr/stamp.hpp"

namespace mrs_vpr {
namespace node {

/**
 * The camera frames each recent keyframe stands for after it: those keyframing left out as too similar
 * to it, which is what a robot standing still (or a view that does not change) gives. One is kept per
 * `spacing` of their stamps, from one `spacing` after the keyframe on, so that a closure of the
 * keyframe can also be stated, once a period, for the time the robot stood there. Without them a stop
 * stays silent however long it lasts: it adds no keyframe, so continuous mode asks nothing about it.
 *
 * Only the `keyframes_kept` newest keyframes are remembered (by default far more than the half sequence
 * back that a centred question localises), each with at most `frames_per_keyframe` frames (the first
 * of a long stop), so that a robot parked for hours neither grows this nor floods its subscribers
 * when it drives on. Frames are offered in the order they came.
 * No ROS inside; the caller locks.
 */
class StandingFrames {
 public:
  /// `spacing` in seconds.
  explicit StandingFrames(double spacing, std::size_t keyframes_kept = 1024, std::size_t frames_per_keyframe = 100)
      : spacing_ns_(static_cast<std::int64_t>(spacing * 1e9)),
        keyframes_kept_(keyframes_kept),
        frames_per_keyframe_(frames_per_keyframe) {}

  /// A frame became a keyframe.
  void keyframe(Stamp stamp) {
    keyframes_.push_back({stamp, stamp, {}});
    while (keyframes_.size() > keyframes_kept_) keyframes_.pop_front();
  }

  /// A frame was left out as too similar to the newest keyframe.
  void tooSimilar(Stamp stamp) {
    if (keyframes_.empty()) return;
    Keyframe& newest = keyframes_.back();
    if (newest.standing.size() >= frames_per_keyframe_) return;
    if (stamp.nanoseconds() - newest.last_kept.nanoseconds() < spacing_ns_) return;
    newest.standing.push_back(stamp);
    newest.last_kept = stamp;
  }

  /// The frames kept for the keyframe of this stamp, oldest first (none when it is not remembered, or
  /// unstamped: then it cannot be told from others).
  std::vector<Stamp> of(Stamp keyframe) const {
    if (keyframe.isZero()) return {};
    for (auto it = keyframes_.rbegin(); it != keyframes_.rend(); ++it) {
      if (it->stamp == keyframe) return it->standing;
    }
    return {};
  }

  void clear() { keyframes_.clear(); }

 private:
  struct Keyframe {
    Stamp stamp;
    Stamp last_kept;
    std::vector<Stamp> standing;
  };

  std::int64_t spacing_ns_;
  std::size_t keyframes_kept_;
  std::size_t frames_per_keyframe_;
  std::deque<Keyframe> keyframes_;
};

/**
 * The standing frames of continuous mode's last accepted keyframe that are still to be restated: those
 * it has when its answer comes, and those it gains afterwards. A causal question (or one of two
 * keyframes) localises the newest keyframe before the robot's stop there has given any frame, and a
 * stop adds no keyframe that would bring a new question; so they are taken again at every period.
 * No ROS inside; the caller locks.
 */
class PendingRestatements {
 public:
  /// An answer localising `keyframe` was accepted: its frames are restated from the first.
  void accepted(Stamp keyframe) {
    keyframe_ = keyframe;
    restated_ = 0;
  }

  /// The frames of the last accepted keyframe not taken yet, oldest first.
  std::vector<Stamp> take(const StandingFrames& frames) {
    const std::vector<Stamp> all = frames.of(keyframe_);
    if (all.size() <= restated_) return {};
    std::vector<Stamp> fresh(all.begin() + static_cast<std::ptrdiff_t>(restated_), all.end());
    restated_ = all.size();
    return fresh;
  }

  void clear() { accepted(Stamp()); }

  /// The closure localising `keyframe` was rejected (~reject_closure): when it is the one restated, its
  /// frames are restated no more. Returns whether it was.
  bool reject(Stamp keyframe) {
    if (keyframe_.isZero() || keyframe_ != keyframe) return false;
    clear();
    return true;
  }

 private:
  Stamp keyframe_;
  std::size_t restated_ = 0;
};

}  // namespace node
}  // namespace mrs_vpr
