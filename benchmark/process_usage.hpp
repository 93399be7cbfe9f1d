#pragma once

// What this process uses of the machine: resident memory and CPU time, as the benchmarks report them.

#include <utility>

namespace mrs_vpr {
namespace benchmark {

/// Resident and peak resident memory of this process [bytes], from /proc/self/status.
std::pair<long long, long long> residentBytes();

/// Hands freed heap back to the system and lowers the peak resident memory to the resident memory
/// now, so that a later peak is one step's alone; false where the peak cannot be reset.
bool resetPeakResident();

/// CPU time of this process (every thread) [s].
double processCpuSeconds();

}  // namespace benchmark
}  // namespace mrs_vpr
