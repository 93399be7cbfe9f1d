#pragma once

#include <chrono>
#include <mutex>
#include <string>

#include <ros/callback_queue.h>
#include <ros/ros.h>

#include "mrs_vpr/MapInfo.h"

namespace mrs_vpr {
namespace testing_support {

/// The ~map_info of a running node, for tests that wait until its map reaches a state.
///
/// Messages go to a callback queue of this object's own, which it serves itself inside waitFor()
/// and latest(): it works the same whether or not a spinner serves the global queue, and never
/// runs another subscription's callback on the test's thread.
class MapInfoWatch {
 public:
  /// `node` is the node's name as `nh` resolves it, e.g. "/mrs_vpr" or "mrs_vpr_debug".
  MapInfoWatch(ros::NodeHandle& nh, const std::string& node) {
    ros::SubscribeOptions options = ros::SubscribeOptions::create<mrs_vpr::MapInfo>(
        node + "/map_info", 10,
        [this](const mrs_vpr::MapInfo::ConstPtr& info) {
          std::lock_guard<std::mutex> lock(mutex_);
          latest_ = *info;
          received_ = true;
        },
        ros::VoidPtr(), &queue_);
    sub_ = nh.subscribe(options);
  }
  MapInfoWatch(const MapInfoWatch&) = delete;
  MapInfoWatch& operator=(const MapInfoWatch&) = delete;

  /// Waits up to `timeout` seconds of wall-clock time until the newest message satisfies
  /// `predicate`; whether it did. Only the newest is judged, so that a message queued before a
  /// change cannot pass for the node's present state.
  template <typename Predicate>
  bool waitFor(Predicate predicate, double timeout) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout);
    queue_.callAvailable();
    while (true) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        const mrs_vpr::MapInfo& newest = latest_;
        if (received_ && predicate(newest)) return true;
      }
      if (!ros::ok() || std::chrono::steady_clock::now() >= deadline) return false;
      queue_.callAvailable(ros::WallDuration(0.02));  // Returns as soon as messages come.
    }
  }

  /// The newest message received so far (a default MapInfo before the first).
  mrs_vpr::MapInfo latest() {
    queue_.callAvailable();
    std::lock_guard<std::mutex> lock(mutex_);
    return latest_;
  }

 private:
  ros::CallbackQueue queue_;  // Declared before sub_, which must go first.
  ros::Subscriber sub_;
  std::mutex mutex_;
  mrs_vpr::MapInfo latest_;
  bool received_ = false;
};

}  // namespace testing_support
}  // namespace mrs_vpr
