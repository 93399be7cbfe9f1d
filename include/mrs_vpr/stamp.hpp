#pragma once

#include <cstdint>
#include <string>

namespace mrs_vpr {

/**
 * The time stamp of a frame, exact: whole nanoseconds since the Unix epoch. Its range is that of ROS
 * 1's time (32-bit unsigned seconds and nanoseconds), 0 to 4294967295.999999999 s, so that every
 * stamp of a map can be published again; a value outside it is refused with std::invalid_argument.
 * A double cannot hold such stamps exactly (4294967295.999999999 becomes 4294967296.0, beyond the
 * range): fromSeconds() and seconds() are for users who only have seconds. Zero means "no stamp".
 */
class Stamp {
 public:
  /// The latest stamp: 4294967295 s and 999999999 ns.
  static constexpr std::int64_t kMaxNanoseconds = 4294967295LL * 1000000000LL + 999999999LL;

  /// No stamp (0).
  constexpr Stamp() = default;

  /// Throws std::invalid_argument naming the value when it is negative or later than kMaxNanoseconds.
  static Stamp fromNanoseconds(std::int64_t nanoseconds);
  /// Seconds and nanoseconds as ROS keeps them; `nanoseconds` may exceed a second (an unnormalised
  /// stamp), but their sum must be in range. Throws std::invalid_argument otherwise.
  static Stamp fromSecondsAndNanoseconds(std::uint32_t seconds, std::uint32_t nanoseconds);
  /// The nearest nanosecond, rounded as ros::Time::fromSec rounds. Throws std::invalid_argument for
  /// NaN, negative seconds and seconds beyond the range.
  static Stamp fromSeconds(double seconds);

  constexpr std::int64_t nanoseconds() const { return nanoseconds_; }
  /// The whole seconds (ROS's `sec`).
  constexpr std::uint32_t wholeSeconds() const { return static_cast<std::uint32_t>(nanoseconds_ / kPerSecond); }
  /// The nanoseconds past the whole second, < 10^9 (ROS's `nsec`).
  constexpr std::uint32_t nanosecondsOfSecond() const { return static_cast<std::uint32_t>(nanoseconds_ % kPerSecond); }
  /// The nearest double (not exact beyond about 10^7 s).
  double seconds() const;
  constexpr bool isZero() const { return nanoseconds_ == 0; }
  /// Seconds with all nine decimals, e.g. "4294967295.999999999".
  std::string toString() const;

  friend constexpr bool operator==(Stamp a, Stamp b) { return a.nanoseconds_ == b.nanoseconds_; }
  friend constexpr bool operator!=(Stamp a, Stamp b) { return a.nanoseconds_ != b.nanoseconds_; }
  friend constexpr bool operator<(Stamp a, Stamp b) { return a.nanoseconds_ < b.nanoseconds_; }
  friend constexpr bool operator<=(Stamp a, Stamp b) { return a.nanoseconds_ <= b.nanoseconds_; }
  friend constexpr bool operator>(Stamp a, Stamp b) { return a.nanoseconds_ > b.nanoseconds_; }
  friend constexpr bool operator>=(Stamp a, Stamp b) { return a.nanoseconds_ >= b.nanoseconds_; }

 private:
  static constexpr std::int64_t kPerSecond = 1000000000LL;
  explicit constexpr Stamp(std::int64_t nanoseconds) : nanoseconds_(nanoseconds) {}

  std::int64_t nanoseconds_ = 0;
};

}  // namespace mrs_vpr
