#include "drive_seed_summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

namespace mrs_vpr {
namespace benchmark {

void printDriveSeedSummary(const std::vector<nlohmann::json>& continuous_rows) {
  // The target for a revisit: accepted right closures in this share of its stretches.
  constexpr double kStretchTarget = 0.7;
  struct Totals {
    int revisits = 0;
    int wrong = 0;
    int wrong_route_frames = 0;
    int restated_wrong = 0;
    int largest_wrong_places = 0;  ///< Over the revisits.
    int largest_wrong_route_frames = 0;
    int accepted = 0;
    double share_sum = 0.0;
    int reaching_target = 0;
    int without_wrong = 0;
    int map_accepted = 0;
    int map_queries = 0;
  };
  std::map<std::string, Totals> by_method;
  for (const nlohmann::json& row : continuous_rows) {
    Totals& totals = by_method[row.at("method").get<std::string>()];
    if (row.at("out_of_map").get<bool>()) {
      totals.map_accepted += row.at("accepted").get<int>();
      totals.map_queries += row.at("queries").get<int>();
      continue;
    }
    ++totals.revisits;
    const int wrong = row.at("accepted_wrong").get<int>();
    const int restated_wrong = row.at("restated_wrong").get<int>();
    totals.wrong += wrong;
    totals.wrong_route_frames += row.at("accepted_wrong_by_route_frame").get<int>();
    totals.restated_wrong += restated_wrong;
    totals.largest_wrong_places =
        std::max(totals.largest_wrong_places, row.at("largest_wrong_error_places").get<int>());
    totals.largest_wrong_route_frames =
        std::max(totals.largest_wrong_route_frames, row.at("largest_wrong_error_route_frames").get<int>());
    totals.accepted += row.at("accepted").get<int>();
    const double share = row.at("stretch_share").is_null() ? 0.0 : row.at("stretch_share").get<double>();
    totals.share_sum += share;
    totals.reaching_target += share >= kStretchTarget ? 1 : 0;
    totals.without_wrong += wrong + restated_wrong == 0 ? 1 : 0;
  }
  for (const auto& [method, t] : by_method) {
    std::printf("drives of %d seeds, %s: revisits accepted %d, wrong %d (by route frame %d), restated wrong %d, "
                "wrong by up to %d places (%d route frames); "
                "stretches confirmed %.3f on average, %d of %d revisits at %.0f%% or more, %d without a wrong "
                "closure; map drives accepted %d of %d answers\n",
                t.revisits, method.c_str(), t.accepted, t.wrong, t.wrong_route_frames, t.restated_wrong,
                t.largest_wrong_places, t.largest_wrong_route_frames,
                t.revisits > 0 ? t.share_sum / t.revisits : std::nan(""), t.reaching_target, t.revisits,
                100.0 * kStretchTarget, t.without_wrong, t.map_accepted, t.map_queries);
  }
}

}  // namespace benchmark
}  // namespace mrs_vpr
