#pragma once

// Totals over the camera drives of several seeds (mrs_vpr_real_benchmark --drive-seeds).

#include <vector>

#include <nlohmann/json.hpp>

namespace mrs_vpr {
namespace benchmark {

/**
 * Totals over the drives of several seeds, per method, from runCameraDrives' continuous-mode rows:
 * the revisits' wrong closures (by places and by route frames), restated wrong ones, the mean share of
 * stretches confirmed, the revisits that reach 70% and those without a wrong closure, and what the
 * map drives accepted (all of it wrong).
 */
void printDriveSeedSummary(const std::vector<nlohmann::json>& continuous_rows);

}  // namespace benchmark
}  // namespace mrs_vpr
