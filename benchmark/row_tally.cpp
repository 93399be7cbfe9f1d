#include "row_tally.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "mrs_vpr/median.hpp"
#include "tools/stopwatch.hpp"

namespace mrs_vpr {
namespace benchmark {

using tools::Clock;
using tools::secondsSince;

double upperMedianOf(std::vector<double> values) { return values.empty() ? 0.0 : upperMedian(values); }

void RowTally::warmUp(const std::function<PlaceAnswer(const char* method)>& ask) {
  ask("mrs");
  ask("seqslam");
}

std::pair<PlaceAnswer, std::optional<PlaceAnswer>> RowTally::time(
    const std::function<PlaceAnswer(const char* method)>& ask, bool with_brute,
    const std::function<bool(const PlaceAnswer&)>& right) {
  auto start = Clock::now();
  const PlaceAnswer mrs = ask("mrs");
  const double mrs_ms_now = secondsSince(start) * 1e3;
  addMrs(mrs, mrs_ms_now, right(mrs));
  if (!with_brute) return {mrs, std::nullopt};
  paired_mrs_ms.push_back(mrs_ms_now);
  start = Clock::now();
  const PlaceAnswer brute = ask("seqslam");
  addBrute(mrs, brute, secondsSince(start) * 1e3, right(brute));
  return {mrs, brute};
}

void RowTally::addMrs(const PlaceAnswer& mrs, double ms, bool right) {
  mrs_ms.push_back(ms);
  mrs_right += right ? 1 : 0;
  mrs_accepted += mrs.match.accepted ? 1 : 0;
  mrs_accepted_wrong += mrs.match.accepted && !right ? 1 : 0;
}

void RowTally::addBrute(const PlaceAnswer& mrs, const PlaceAnswer& brute, double ms, bool right) {
  brute_ms.push_back(ms);
  brute_right += right ? 1 : 0;
  same_frame += mrs.match.reference_index == brute.match.reference_index ? 1 : 0;
  same_accepted += mrs.match.accepted == brute.match.accepted ? 1 : 0;
  confidence_gap =
      std::max(confidence_gap, std::abs(static_cast<double>(mrs.match.confidence - brute.match.confidence)));
}

void RowTally::print(const std::string& map, int length, const char* kind, double load_s, double rss_per_frame,
                     double peak_per_frame) const {
  const double brute = upperMedianOf(brute_ms);
  const double fast = upperMedianOf(mrs_ms);
  char speed_up[32] = "-";
  char same[32] = "-";
  char gap[32] = "-";
  if (!brute_ms.empty()) {
    std::snprintf(speed_up, sizeof(speed_up), "%.1fx", brute / upperMedianOf(paired_mrs_ms));
    std::snprintf(same, sizeof(same), "%d/%d/%d", same_frame, same_accepted, static_cast<int>(brute_ms.size()));
    std::snprintf(gap, sizeof(gap), "%.2f", confidence_gap);
  }
  std::printf("%9s %5d %8s %8.2f %9.0f %9.0f %8.1f %10.1f %6d/%-3d %8s %6d/%-3d %6d/%-3d %10s %6s\n", map.c_str(),
              length, kind, load_s, rss_per_frame, peak_per_frame, fast, brute, mrs_right,
              static_cast<int>(mrs_ms.size()), speed_up, brute_right, static_cast<int>(brute_ms.size()),
              mrs_accepted_wrong, mrs_accepted, same, gap);
  std::fflush(stdout);
}

}  // namespace benchmark
}  // namespace mrs_vpr
