#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "mrs_vpr/parameters.hpp"
#include "mrs_vpr/sequence_matcher.hpp"
#include "support/route_fixture.hpp"

namespace mrs_vpr {
namespace {

using testing_support::globalSearchParams;
using testing_support::routeParameters;
using testing_support::standardRoute;
using testing_support::within;

/// What every method promises on the generated route. Each method's own ways (MRS's levels and
/// hypotheses, the brute force's comparisons) are tested in its own file.
class EveryMethod : public testing::TestWithParam<std::string> {};

TEST_P(EveryMethod, RecoversThePlantedAlignmentOfGlobalQueries) {
  const auto& route = standardRoute();
  const auto matcher = makeMatcher(GetParam(), globalSearchParams());
  for (int length : {100, 150, 200}) {
    for (int start : {0, 60, 130, 199}) {
      const int end = start + length - 1;
      if (end >= route.query.size()) continue;
      const Match match = matcher->match(route.reference.view(), route.query.view(start, end + 1));
      const int truth = route.query_to_reference[static_cast<std::size_t>(end)];
      EXPECT_TRUE(within(match.reference_index, truth, 3))
          << "N = " << length << ", start " << start << ": got " << match.reference_index << ", truth " << truth;
      EXPECT_TRUE(match.accepted) << "N = " << length << ", start " << start << ": confidence "
                                  << match.confidence;
    }
  }
}

// A test sequence as long as the reference is searched; only a longer one is refused.
TEST_P(EveryMethod, SearchesATestSequenceAsLongAsTheReference) {
  const auto& route = standardRoute();
  const auto matcher = makeMatcher(GetParam(), globalSearchParams());
  for (const int frames : {120, 300}) {
    const Match match = matcher->match(route.reference.view(0, frames), route.query.view(0, frames));
    EXPECT_GE(match.reference_index, 0) << frames << " frames";
    EXPECT_THROW(matcher->match(route.reference.view(0, frames), route.query.view(0, frames + 1)),
                 std::invalid_argument)
        << frames << " frames";
  }
}

TEST_P(EveryMethod, CentredAlignmentReportsTheMiddleFrame) {
  const auto& route = standardRoute();
  Parameters params = globalSearchParams();
  params.sequence.alignment = WindowAlignment::kCentred;
  const auto matcher = makeMatcher(GetParam(), params);
  for (int start : {20, 150, 250}) {
    const int length = 128;
    const Match match = matcher->match(route.reference.view(), route.query.view(start, start + length));
    const int truth = route.query_to_reference[static_cast<std::size_t>(start + length / 2)];
    EXPECT_TRUE(within(match.reference_index, truth, 3))
        << "start " << start << ": got " << match.reference_index << ", truth " << truth;
  }
  // Exactly row count / 2 on identical frames, below MRS's coarser levels (100 rows) and with them (128).
  EXPECT_EQ(matcher->match(route.reference.view(), route.reference.view(200, 300)).reference_index, 250);
  EXPECT_EQ(matcher->match(route.reference.view(), route.reference.view(300, 428)).reference_index, 364);
}

TEST_P(EveryMethod, MatchEveryFrameGetsMostFramesRightAndSkipsIncompleteSequences) {
  const auto& route = standardRoute();
  const auto matcher = makeMatcher(GetParam(), routeParameters());  // Per-frame protocol, sequence_length 10.
  const std::vector<Match> matches = matcher->matchEveryFrame(route.reference.view(), route.query.view());
  ASSERT_EQ(matches.size(), static_cast<std::size_t>(route.query.size()));
  for (int frame = 0; frame < 9; ++frame) EXPECT_EQ(matches[static_cast<std::size_t>(frame)].reference_index, -1);
  int correct = 0;
  for (int frame = 9; frame < route.query.size(); ++frame) {
    const Match& match = matches[static_cast<std::size_t>(frame)];
    EXPECT_GE(match.reference_index, 0) << "frame " << frame;
    correct += within(match.reference_index, route.query_to_reference[static_cast<std::size_t>(frame)], 3) ? 1 : 0;
  }
  EXPECT_GE(correct, 0.9 * (route.query.size() - 9)) << correct << " of " << route.query.size() - 9;
}

INSTANTIATE_TEST_SUITE_P(Methods, EveryMethod, testing::Values("seqslam", "mrs"),
                         [](const testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
}  // namespace mrs_vpr
