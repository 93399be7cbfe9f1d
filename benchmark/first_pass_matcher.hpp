#pragma once

// The real-data benchmark's "mrs-first-pass" method: MRS's search for short sequences on any map.

#include <memory>
#include <string>
#include <vector>

#include "mrs_vpr/mrs/level_trace.hpp"
#include "mrs_vpr/mrs_matcher.hpp"
#include "mrs_vpr/parameters.hpp"
#include "mrs_vpr/sequence_matcher.hpp"

namespace mrs_vpr {
namespace benchmark {

/// MRS's search for short sequences (MrsMatcher::matchByFirstPass) on any map, where MrsMatcher::match
/// takes it only on maps large enough for it to pay: its answers, confidences and acceptance can be
/// compared with the brute force's on real frames.
class FirstPassMatcher : public SequenceMatcher {
 public:
  explicit FirstPassMatcher(const Parameters& params);

  Match match(SequenceView reference, SequenceView query) const override { return match(reference, query, nullptr); }
  /// The same, with the first pass traced into `trace` (one level, stride 1) when not null.
  Match match(SequenceView reference, SequenceView query, std::vector<MrsLevelTrace>* trace) const;
  std::string name() const override { return "mrs-first-pass"; }

 private:
  MrsMatcher mrs_;
};

/// The matcher of a --methods item: seqslam, mrs (makeMatcher) or mrs-first-pass.
std::unique_ptr<SequenceMatcher> makeBenchMatcher(const std::string& method, const Parameters& params);

}  // namespace benchmark
}  // namespace mrs_vpr
