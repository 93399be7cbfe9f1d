#pragma once

#include <atomic>
#include <chrono>

namespace mrs_vpr {
namespace node {

/**
 * Tells when the camera has gone silent: no image for kWarnAfter seconds, or for kSlowCameraGaps of its
 * own gaps between images when it sends fewer than one every 1.7 s, since the node started or since the
 * last image. A node started on a topic nobody publishes (a misspelt name, a camera
 * namespace the launch file did not remap) otherwise only said what it listens on, then nothing,
 * however long the user waited for loop closures. Each silence is reported once, and its end once, so
 * that a node kept only to answer ~query about explicit images logs one warning, not one a period.
 * Times are seconds on a steady clock. Thread-safe: images arrive on the camera's thread, and check()
 * runs on a timer's (one thread only).
 */
class CameraSilence {
 public:
  /// Seconds without an image before a silence is reported.
  static constexpr double kWarnAfter = 5.0;
  /// A slow camera's silence lasts this many of its last gaps between two images.
  static constexpr double kSlowCameraGaps = 3.0;

  /// What check() found.
  enum class Change {
    kNone,       ///< Nothing new to say.
    kSilent,     ///< A silence began kWarnAfter or more seconds ago, and is reported now.
    kImagesBack  ///< Images arrive again after a silence that was reported.
  };

  /// When the node began to listen for images: a silence counts from then.
  void listenFrom(double start) { last_image_.store(start, std::memory_order_relaxed); }

  /// An image arrived at `now`.
  void imageArrived(double now) {
    const double previous = last_image_.exchange(now, std::memory_order_relaxed);
    if (any_image_.exchange(true, std::memory_order_relaxed)) gap_.store(now - previous, std::memory_order_relaxed);
  }

  /// Called periodically; says whether a silence has begun or ended since the last call.
  Change check(double now) {
    const bool silent = silentFor(now) >= silenceAfter();
    if (!reported_ && silent) {
      reported_ = true;
      return Change::kSilent;
    }
    if (reported_ && !silent) {
      reported_ = false;
      return Change::kImagesBack;
    }
    return Change::kNone;
  }

  /// Seconds without an image that make a silence: kWarnAfter, or more for a slow camera.
  double silenceAfter() const {
    const double gap = gap_.load(std::memory_order_relaxed);
    return gap * kSlowCameraGaps > kWarnAfter ? gap * kSlowCameraGaps : kWarnAfter;
  }

  /// Seconds since the last image (since the start when none came), at `now`.
  double silentFor(double now) const { return now - last_image_.load(std::memory_order_relaxed); }
  /// Whether any image has arrived since the start.
  bool anyImage() const { return any_image_.load(std::memory_order_relaxed); }

 private:
  std::atomic<double> last_image_{0.0};
  std::atomic<bool> any_image_{false};
  std::atomic<double> gap_{0.0};  ///< Between the last two images.
  bool reported_ = false;  ///< check()'s thread only.
};

/// Seconds on the steady clock, for CameraSilence.
inline double steadySeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace node
}  // namespace mrs_vpr
