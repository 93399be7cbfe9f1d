#include "truth_diagnosis.hpp"

#include <cstdio>
#include <cstdlib>

namespace mrs_vpr {
namespace benchmark {
namespace {

/// The 1-based rank of the first candidate within `tolerance` of a true index; 0 when none is.
int rankOf(const std::vector<int>& candidates, const std::vector<int>& truth, int tolerance) {
  for (std::size_t r = 0; r < candidates.size(); ++r) {
    for (int t : truth) {
      if (std::abs(candidates[r] - t) <= tolerance) return static_cast<int>(r) + 1;
    }
  }
  return 0;
}

void printRanks(const std::map<int, int>& ranks, int queries) {
  for (int top : {1, 2, 3, 5, 8, 20, 50}) {
    int cumulative = 0;
    for (const auto& [rank, count] : ranks) {
      if (rank >= 1 && rank <= top) cumulative += count;
    }
    std::printf(" top%d %.2f", top, static_cast<double>(cumulative) / queries);
  }
  const auto lost = ranks.find(0);
  std::printf(" lost %.2f\n", lost == ranks.end() ? 0.0 : static_cast<double>(lost->second) / queries);
}

}  // namespace

void TruthDiagnosis::add(const std::vector<MrsLevelTrace>& trace, const std::vector<int>& truth, int tolerance,
                         double accept_threshold) {
  if (levels_.size() < trace.size()) levels_.resize(trace.size());
  for (std::size_t l = 0; l < trace.size(); ++l) {
    LevelCounts& counts = levels_[l];
    counts.stride = trace[l].stride;
    ++counts.queries;
    const int rank = rankOf(trace[l].candidates, truth, tolerance + trace[l].stride);
    counts.ranks[rank]++;
    if (l == 0) {
      const int table_rank = rankOf(trace[l].table_minima, truth, tolerance + trace[l].stride);
      counts.table_ranks[table_rank]++;
      // The coarse table alone would have accepted a wrong place: the finer levels had to catch it.
      if (table_rank != 1 && trace[l].table_confidence >= accept_threshold) ++confidently_wrong_;
    }
  }
}

void TruthDiagnosis::print(const std::string& setting) const {
  std::printf("  diagnose %-24s coarse table's lowest minimum wrong at an accepted confidence: %d queries\n",
              setting.c_str(), confidently_wrong_);
  for (const LevelCounts& counts : levels_) {
    std::printf("  diagnose %-24s stride %2d: truth among hypotheses at rank", setting.c_str(), counts.stride);
    printRanks(counts.ranks, counts.queries);
    if (!counts.table_ranks.empty()) {
      std::printf("  diagnose %-24s stride %2d: truth among the table's distinct minima at rank", setting.c_str(),
                  counts.stride);
      printRanks(counts.table_ranks, counts.queries);
    }
  }
}

}  // namespace benchmark
}  // namespace mrs_vpr
