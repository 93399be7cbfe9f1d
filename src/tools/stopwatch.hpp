#pragma once

// Wall time for the figures the tools and the benchmarks print.

#include <chrono>

namespace mrs_vpr {
namespace tools {

using Clock = std::chrono::steady_clock;

/// Seconds since `start`.
inline double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace tools
}  // namespace mrs_vpr
