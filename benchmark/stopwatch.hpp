#pragma once

// Wall time for the map-scale benchmark's figures.

#include <chrono>

namespace mrs_vpr {
namespace benchmark {

using Clock = std::chrono::steady_clock;

/// Seconds since `start`.
inline double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace benchmark
}  // namespace mrs_vpr
