#include "process_usage.hpp"

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

void resetPeakResident() {
  std::ofstream("/proc/self/clear_refs") << "5";  // Linux: "5" resets VmHWM
}

double processCpuSeconds() {
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

}  // namespace benchmark
}  // namespace mrs_vpr
