#include "real_report.hpp"

#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "tools/summary_json.hpp"

namespace mrs_vpr {
namespace benchmark {

void Report::printHeader() {
  std::printf("%-34s %-8s %7s %7s %7s %7s %9s %8s %8s %10s\n", "setting", "method", "queries", "success", "R@100P",
              "PR-AUC", "accepted", "acc.P", "acc.R", "median ms");
}

void Report::row(const std::string& setting, const std::string& method, const EvaluationSummary& s,
                 const RowFacts& facts) {
  std::printf("%-34s %-8s %7d %7.3f %7.3f %7.3f %9d %8.3f %8.3f %10.3f\n", setting.c_str(), method.c_str(), s.queries,
              s.top1, s.recall_at_100_precision, s.pr_auc, s.accepted, s.accepted_precision, s.accepted_recall,
              s.median_time_ms);
  std::fflush(stdout);
  rows_.push_back({{"setting", setting},
                   {"method", method},
                   {"protocol", facts.protocol},
                   {"out_of_map", facts.out_of_map},
                   {"reference_frames", facts.reference_frames},
                   {"sequence_length", facts.sequence_length},
                   {"summary", tools::summaryToJson(s)}});
}

void Report::add(const std::vector<nlohmann::json>& rows) { rows_.insert(rows_.end(), rows.begin(), rows.end()); }

void Report::write(const std::string& path, nlohmann::json settings) const {
  if (path.empty()) return;
  settings["rows"] = rows_;
  std::ofstream file(path);
  file << settings.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";  // Any bytes of a path.
  if (!file) throw std::runtime_error("cannot write '" + path + "'");
  std::fprintf(stderr, "wrote %s\n", path.c_str());
}

}  // namespace benchmark
}  // namespace mrs_vpr
