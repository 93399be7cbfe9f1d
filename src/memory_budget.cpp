#include "mrs_vpr/memory_budget.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>

namespace mrs_vpr {
namespace {

std::string gigabytes(std::uint64_t bytes) {
  std::ostringstream text;
  text.precision(1);
  text << std::fixed << static_cast<double>(bytes) / 1e9 << " GB";
  return text.str();
}

}  // namespace

std::optional<std::uint64_t> availableMemoryBytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string line;
  while (std::getline(meminfo, line)) {
    std::istringstream fields(line);
    std::string key;
    std::uint64_t kilobytes = 0;
    if (fields >> key >> kilobytes && key == "MemAvailable:") return kilobytes * 1024;  // "MemAvailable: N kB"
  }
  return std::nullopt;
}

void requireAvailableMemory(std::uint64_t bytes, const std::string& what, const std::string& remedy,
                            std::optional<std::uint64_t> available) {
  if (!available || bytes <= *available) return;
  throw std::invalid_argument(what + " needs " + gigabytes(bytes) + ", more than the " + gigabytes(*available) +
                              " of memory available: " + remedy);
}

}  // namespace mrs_vpr
