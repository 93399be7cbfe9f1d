#include "first_pass_matcher.hpp"

namespace mrs_vpr {
namespace benchmark {

FirstPassMatcher::FirstPassMatcher(const Parameters& params)
    : SequenceMatcher(params.sequence), mrs_(params.sequence, params.mrs, params.descriptor) {}

Match FirstPassMatcher::match(SequenceView reference, SequenceView query, std::vector<MrsLevelTrace>* trace) const {
  return mrs_.matchByFirstPass(reference, query, trace);
}

std::unique_ptr<SequenceMatcher> makeBenchMatcher(const std::string& method, const Parameters& params) {
  if (method == "mrs-first-pass") return std::make_unique<FirstPassMatcher>(params);
  return makeMatcher(method, params);
}

}  // namespace benchmark
}  // namespace mrs_vpr
