#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace mrs_vpr {

/// Bytes the system can still give without swapping (Linux's MemAvailable), or nullopt where that is
/// not known.
std::optional<std::uint64_t> availableMemoryBytes();

/**
 * Throws std::invalid_argument, naming `what`, both sizes and `remedy`, when `bytes` exceed
 * `available` (when known). The kernel grants such an allocation (it overcommits) and the process
 * then fills it: the machine swaps, or the process is killed with the map it holds. Refusing the
 * request keeps a node running.
 */
void requireAvailableMemory(std::uint64_t bytes, const std::string& what, const std::string& remedy,
                            std::optional<std::uint64_t> available = availableMemoryBytes());

}  // namespace mrs_vpr
