#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "mrs_vpr/parameters.hpp"
#include "mrs_vpr/seqslam_matcher.hpp"
#include "mrs_vpr/sequence_matcher.hpp"
#include "support/route_fixture.hpp"
#include "support/error_message.hpp"

namespace mrs_vpr {
namespace {

using testing_support::invalidArgumentMessage;
using testing_support::globalSearchParams;
using testing_support::routeParameters;
using testing_support::standardRoute;
using testing_support::within;

TEST(MakeMatcher, BuildsBothMethodsAndRejectsOthers) {
  const Parameters params = routeParameters();
  EXPECT_EQ(makeMatcher("seqslam", params)->name(), "seqslam");
  EXPECT_EQ(makeMatcher("mrs", params)->name(), "mrs");
  const std::string message = invalidArgumentMessage([&] { makeMatcher("fast", params); });
  EXPECT_NE(message.find("unknown method 'fast'"), std::string::npos) << message;
  Parameters bad = params;
  bad.sequence.match_exclusion = -3;
  const std::string bad_message = invalidArgumentMessage([&] { makeMatcher("seqslam", bad); });
  EXPECT_NE(bad_message.find("sequence/match_exclusion"), std::string::npos) << bad_message;
}

TEST(SeqSlamMatcher, ComparesEveryQueryFrameWithEveryReferenceFrame) {
  const auto& route = standardRoute();
  const auto matcher = makeMatcher("seqslam", globalSearchParams());
  for (int length : {100, 150, 200}) {
    const Match match = matcher->match(route.reference.view(), route.query.view(0, length));
    EXPECT_EQ(match.comparisons, static_cast<long long>(length) * route.reference.size()) << "N = " << length;
  }
}

TEST(SeqSlamMatcher, IdenticalFramesGiveTheExactEndIndex) {
  const auto& route = standardRoute();
  const auto matcher = makeMatcher("seqslam", routeParameters());
  for (int end : {99, 345, 599}) {
    const Match match = matcher->match(route.reference.view(), route.reference.view(end - 79, end + 1));
    EXPECT_EQ(match.reference_index, end);
    EXPECT_LT(match.score, 0.9F);
  }
}

TEST(SeqSlamMatcher, MatchEveryFrameAgreesWithMatchOnEachSequence) {
  const auto& route = standardRoute();
  const auto matcher = makeMatcher("seqslam", routeParameters());
  const SequenceView query = route.query.view(100, 160);
  const std::vector<Match> every = matcher->matchEveryFrame(route.reference.view(), query);
  for (int frame : {9, 30, 59}) {
    const Match single = matcher->match(route.reference.view(), query.slice(frame - 9, frame + 1));
    EXPECT_EQ(every[static_cast<std::size_t>(frame)].reference_index, single.reference_index) << frame;
    EXPECT_FLOAT_EQ(every[static_cast<std::size_t>(frame)].score, single.score) << frame;
  }
}

TEST(SeqSlamMatcher, CentredMatchEveryFrameSkipsBothEnds) {
  const auto& route = standardRoute();
  Parameters params = routeParameters();
  params.sequence.alignment = WindowAlignment::kCentred;
  const auto matcher = makeMatcher("seqslam", params);
  // Identical frames: every complete frame maps exactly onto itself (+100).
  const std::vector<Match> matches = matcher->matchEveryFrame(route.reference.view(), route.reference.view(100, 160));
  for (int frame = 0; frame < 60; ++frame) {
    const int expected = (frame < 5 || frame > 55) ? -1 : 100 + frame;
    EXPECT_EQ(matches[static_cast<std::size_t>(frame)].reference_index, expected) << "frame " << frame;
  }
}

TEST(SeqSlamMatcher, RepeatedCallsGiveIdenticalMatches) {
  const auto& route = standardRoute();
  const auto matcher = makeMatcher("seqslam", globalSearchParams());
  const SequenceView query = route.query.view(50, 200);
  const Match a = matcher->match(route.reference.view(), query);
  const Match b = makeMatcher("seqslam", globalSearchParams())->match(route.reference.view(), query);
  EXPECT_EQ(a.reference_index, b.reference_index);
  EXPECT_EQ(a.score, b.score);
  EXPECT_EQ(a.confidence, b.confidence);
  EXPECT_EQ(a.comparisons, b.comparisons);
}

TEST(SeqSlamMatcher, BadInputsThrowWithAClearMessage) {
  const auto& route = standardRoute();
  const SeqSlamMatcher matcher{SequenceParams{}};
  const std::string too_short =
      invalidArgumentMessage([&] { matcher.match(route.reference.view(), route.query.view(0, 1)); });
  EXPECT_NE(too_short.find("at least 2 frames"), std::string::npos) << too_short;
  const std::string too_long =
      invalidArgumentMessage([&] { matcher.match(route.reference.view(0, 50), route.query.view(0, 60)); });
  EXPECT_NE(too_long.find("longer than the reference"), std::string::npos) << too_long;
  DescriptorSequence small(16);
  small.append(cv::Mat(1, 16, CV_8U, cv::Scalar(1)));
  small.append(cv::Mat(1, 16, CV_8U, cv::Scalar(2)));
  const std::string sizes = invalidArgumentMessage([&] { matcher.match(route.reference.view(), small.view()); });
  EXPECT_NE(sizes.find("16 bytes"), std::string::npos) << sizes;
  EXPECT_NE(sizes.find("2048"), std::string::npos) << sizes;
  EXPECT_THROW(matcher.matchEveryFrame(route.reference.view(), small.view()), std::invalid_argument);
}

}  // namespace
}  // namespace mrs_vpr
