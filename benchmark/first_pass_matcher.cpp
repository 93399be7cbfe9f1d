#include "first_pass_matcher.hpp"

#include "mrs_vpr/acceptance.hpp"
#include "mrs_vpr/mrs/short_sequence_search.hpp"
#include "mrs_vpr/trajectory_search.hpp"

namespace mrs_vpr {
namespace benchmark {

FirstPassMatcher::FirstPassMatcher(const Parameters& params)
    : SequenceMatcher(params.sequence), compact_(makeCompactCells(params.descriptor)) {}

Match FirstPassMatcher::match(SequenceView reference, SequenceView query, std::vector<MrsLevelTrace>* trace) const {
  checkInputs(reference, query);
  MrsLevelTrace level;
  Match match = searchShortSequence(reference, query, sequence_, *compact_, kShortSearchHypotheses, &level);
  if (trace != nullptr) trace->push_back(level);
  placeAnswer(match, reference, query, wholeSequenceRows(query.count, sequence_.alignment));
  applyAcceptance(match, sequence_);
  return match;
}

std::unique_ptr<SequenceMatcher> makeBenchMatcher(const std::string& method, const Parameters& params) {
  if (method == "mrs-first-pass") return std::make_unique<FirstPassMatcher>(params);
  return makeMatcher(method, params);
}

}  // namespace benchmark
}  // namespace mrs_vpr
