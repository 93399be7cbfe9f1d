#include "process_usage.hpp"

#include <malloc.h>
#include <time.h>

#include <fstream>
#include <string>

namespace mrs_vpr {
namespace benchmark {

std::pair<long long, long long> residentBytes() {
  std::ifstream status("/proc/self/status");
  long long rss = 0;
  long long hwm = 0;
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("VmRSS:", 0) == 0) rss = std::stoll(line.substr(6)) * 1024;
    if (line.rfind("VmHWM:", 0) == 0) hwm = std::stoll(line.substr(6)) * 1024;
  }
  return {rss, hwm};
}

bool resetPeakResident() {
  // Freed memory the allocator keeps would otherwise be reused unseen by the next step's peak.
  malloc_trim(0);
  std::ofstream clear_refs("/proc/self/clear_refs");
  clear_refs << "5" << std::flush;  // Linux: "5" resets VmHWM
  const auto [rss, peak] = residentBytes();
  return clear_refs.good() && peak - rss < 1024 * 1024;
}

double processCpuSeconds() {
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

}  // namespace benchmark
}  // namespace mrs_vpr
