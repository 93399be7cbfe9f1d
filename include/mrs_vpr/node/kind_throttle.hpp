#pragma once

#include <cctype>
#include <iterator>
#include <map>
#include <mutex>
#include <string>

namespace mrs_vpr {
namespace node {

/**
 * Lets a warning of each kind through once a `period` (seconds on a steady clock), whatever other
 * kinds come between: a camera that sends broken frames of two kinds, one after the other, has both
 * reported, and a client that makes two mistakes in turn sees both, while neither floods the log.
 * ROS's throttle, one period for every message of a call site, would hide the second kind. Thread-safe.
 */
class KindThrottle {
 public:
  /// Kinds told apart within one period at most; further kinds share one period among them.
  static constexpr std::size_t kRemembered = 64;

  explicit KindThrottle(double period) : period_(period) {}

  /// Whether a warning of `kind`, at `now`, is to be logged; if so, the kind's period starts again.
  bool allows(const std::string& kind, double now) {
    const std::lock_guard<std::mutex> lock(mutex_);
    auto last = let_through_.find(kind);
    if (last == let_through_.end() && let_through_.size() >= kRemembered) {
      forgetOlderThan(now - period_);
      // Still as many kinds within one period: the rest share one, rather than flood the log.
      if (let_through_.size() >= kRemembered) last = let_through_.emplace(kOtherKinds, -period_).first;
    }
    if (last != let_through_.end() && now - last->second < period_) return false;
    let_through_[last != let_through_.end() ? last->first : kind] = now;
    return true;
  }

  /// Kinds remembered now (at most kRemembered + 1): for tests.
  std::size_t remembered() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return let_through_.size();
  }

 private:
  void forgetOlderThan(double time) {
    for (auto it = let_through_.begin(); it != let_through_.end();) {
      it = it->second < time ? let_through_.erase(it) : std::next(it);
    }
  }

  /// The key the kinds beyond kRemembered share: a control character no message holds.
  static constexpr const char* kOtherKinds = "\x01 other kinds";

  const double period_;
  mutable std::mutex mutex_;
  std::map<std::string, double> let_through_;  ///< Each kind's last time let through.
};

/// `message` with each run of digits written as '#': the kind of a problem whose message names a
/// frame's own numbers (its size, its bytes), so that frames broken the same way are one kind.
inline std::string kindOf(const std::string& message) {
  std::string kind;
  bool in_number = false;
  for (const char c : message) {
    const bool digit = std::isdigit(static_cast<unsigned char>(c)) != 0;
    if (!digit) {
      kind += c;
    } else if (!in_number) {
      kind += '#';
    }
    in_number = digit;
  }
  return kind;
}

}  // namespace node
}  // namespace mrs_vpr
