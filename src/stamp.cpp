#include "mrs_vpr/stamp.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace mrs_vpr {
namespace {

constexpr std::int64_t kPerSecond = 1000000000LL;
constexpr const char* kRange = "0 .. 4294967295.999999999 s, the range of a ROS time";

std::string secondsText(std::int64_t nanoseconds) {
  const bool negative = nanoseconds < 0;
  // Both parts positive, also for the most negative value, whose negation does not exist.
  const auto magnitude =
      negative ? 0 - static_cast<std::uint64_t>(nanoseconds) : static_cast<std::uint64_t>(nanoseconds);
  char text[48];
  std::snprintf(text, sizeof(text), "%s%llu.%09llu", negative ? "-" : "",
                static_cast<unsigned long long>(magnitude / kPerSecond),
                static_cast<unsigned long long>(magnitude % kPerSecond));
  return text;
}

}  // namespace

Stamp Stamp::fromNanoseconds(std::int64_t nanoseconds) {
  if (nanoseconds < 0 || nanoseconds > kMaxNanoseconds) {
    throw std::invalid_argument("stamp " + secondsText(nanoseconds) + " s is outside " + kRange);
  }
  return Stamp(nanoseconds);
}

Stamp Stamp::fromSecondsAndNanoseconds(std::uint32_t seconds, std::uint32_t nanoseconds) {
  // At most 4294967295 * 10^9 + 4294967295: no overflow in 64 bits.
  return fromNanoseconds(static_cast<std::int64_t>(seconds) * kPerSecond + static_cast<std::int64_t>(nanoseconds));
}

Stamp Stamp::fromSeconds(double seconds) {
  if (std::isnan(seconds)) throw std::invalid_argument(std::string("a stamp of NaN seconds is outside ") + kRange);
  const double whole = std::floor(seconds);
  if (whole < 0.0 || whole > 4294967295.0) {
    char text[64];
    std::snprintf(text, sizeof(text), "%.17g", seconds);
    throw std::invalid_argument("stamp " + std::string(text) + " s is outside " + kRange);
  }
  // seconds - whole is exact, so the fraction is rounded once, as ros::Time::fromSec rounds it.
  const auto fraction = static_cast<std::int64_t>(std::llround((seconds - whole) * 1e9));
  return fromNanoseconds(static_cast<std::int64_t>(whole) * kPerSecond + fraction);
}

double Stamp::seconds() const {
  // As ros::Time::toSec computes it, so that both give the same double.
  return static_cast<double>(wholeSeconds()) + static_cast<double>(nanosecondsOfSecond()) * 1e-9;
}

std::string Stamp::toString() const { return secondsText(nanoseconds_); }

}  // namespace mrs_vpr
