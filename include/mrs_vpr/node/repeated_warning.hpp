#pragma once

#include <limits>
#include <mutex>
#include <string>

namespace mrs_vpr {
namespace node {

/**
 * Lets a warning through unless it repeats the last one let through within `period` seconds: a
 * caller's different mistakes are each logged at once, and one mistake made again and again (a client
 * polling ~query before the map can answer) once a period. ROS's throttle, one period for every
 * message of a call site, would hide the second of two different mistakes. Times are seconds on a
 * steady clock. Thread-safe.
 */
class RepeatedWarning {
 public:
  explicit RepeatedWarning(double period) : period_(period) {}

  /// Whether `message`, at `now`, is to be logged; if so, it is the last one let through.
  bool allows(const std::string& message, double now) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (message == last_ && now - last_time_ < period_) return false;
    last_ = message;
    last_time_ = now;
    return true;
  }

 private:
  const double period_;
  std::mutex mutex_;
  std::string last_;
  double last_time_ = -std::numeric_limits<double>::infinity();
};

}  // namespace node
}  // namespace mrs_vpr
