#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>

namespace mrs_vpr {
namespace node {

/**
 * Tells when the camera has gone silent: no image for silenceAfter() seconds, since the node began to
 * listen or since the last image. A node started on a topic nobody publishes (a misspelt name, a camera
 * namespace the launch file did not remap) otherwise only said what it listens on, then nothing,
 * however long the user waited for loop closures. Each silence is reported once, and its end once.
 * Each silence reported makes the next one wait twice as long, up to kLongestWait, so that a camera
 * that pauses by design (triggered, gated by motion, a slow time-lapse) is reported a few times, not at
 * every pause. Times are seconds on a steady clock. Thread-safe: images arrive on the camera's thread,
 * and check() runs on a timer's (one thread only).
 */
class CameraSilence {
 public:
  /// Seconds without an image before the first silence is reported.
  static constexpr double kFirstWait = 5.0;
  /// The longest wait a silence needs, however many were reported.
  static constexpr double kLongestWait = 60.0;

  /// What check() found.
  enum class Change {
    kNone,       ///< Nothing new to say.
    kSilent,     ///< A silence has lasted silenceAfter() seconds, and is reported now.
    kImagesBack  ///< Images arrive again after a silence that was reported.
  };

  /// When the node began to listen for images: a silence counts from then.
  void listenFrom(double start) { last_image_.store(start, std::memory_order_relaxed); }

  /// An image arrived at `now`.
  void imageArrived(double now) {
    last_image_.store(now, std::memory_order_relaxed);
    any_image_.store(true, std::memory_order_relaxed);
  }

  /// Called periodically; says whether a silence has begun or ended since the last call.
  Change check(double now) {
    const bool silent = silentFor(now) >= wait_;
    if (!reported_ && silent) {
      reported_ = true;
      return Change::kSilent;
    }
    if (reported_ && !silent) {
      reported_ = false;
      wait_ = std::min(2.0 * wait_, kLongestWait);
      return Change::kImagesBack;
    }
    return Change::kNone;
  }

  /// Seconds without an image that make the next silence (check()'s thread).
  double silenceAfter() const { return wait_; }
  /// Seconds since the last image (since the start when none came), at `now`.
  double silentFor(double now) const { return now - last_image_.load(std::memory_order_relaxed); }
  /// Whether any image has arrived since the start.
  bool anyImage() const { return any_image_.load(std::memory_order_relaxed); }

 private:
  std::atomic<double> last_image_{0.0};
  std::atomic<bool> any_image_{false};
  bool reported_ = false;    ///< check()'s thread only, as is wait_.
  double wait_ = kFirstWait;
};

/// Seconds on the steady clock, for CameraSilence.
inline double steadySeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace node
}  // namespace mrs_vpr
