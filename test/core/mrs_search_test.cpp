#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "mrs_vpr/mrs_search.hpp"
#include "mrs_vpr/parameters.hpp"
#include "mrs_vpr/sequence_matcher.hpp"
#include "route_fixture.hpp"
#include "error_message.hpp"

namespace mrs_vpr {
namespace {

using testing_support::invalidArgumentMessage;
using testing_support::longRoute;
using testing_support::globalSearchParams;
using testing_support::standardRoute;
using testing_support::within;

void expectIdentical(const Match& a, const Match& b) {
  EXPECT_EQ(a.reference_index, b.reference_index);
  EXPECT_EQ(a.score, b.score);
  EXPECT_EQ(a.confidence, b.confidence);
  EXPECT_EQ(a.sequence_difference, b.sequence_difference);
  EXPECT_EQ(a.comparisons, b.comparisons);
}

/// A copy of `reference` that keeps the pooled cells MRS reads, as the node's map does.
DescriptorSequence withKeptCells(const DescriptorSequence& reference, const MrsParams& mrs) {
  DescriptorSequence kept = reference;
  kept.keepPooledCells(mrs.levels, mrs.pixel_pooling);
  return kept;
}

TEST(MrsSearch, LevelsForKeepsEnoughCoarseFrames) {
  const MrsSearch search(SequenceParams{}, MrsParams{});  // levels 3, min_coarse_frames 64
  EXPECT_EQ(search.levelsFor(10), 0);
  EXPECT_EQ(search.levelsFor(126), 0);  // 63 cells at stride 2: too few ...
  EXPECT_EQ(search.levelsFor(127), 1);  // ... 64 cells at stride 2 (frames 0, 2, ..., 126).
  EXPECT_EQ(search.levelsFor(200), 1);  // 50 cells at stride 4: too few.
  EXPECT_EQ(search.levelsFor(252), 1);  // 63 cells at stride 4 ...
  EXPECT_EQ(search.levelsFor(253), 2);  // ... 64.
  EXPECT_EQ(search.levelsFor(300), 2);  // 75 at stride 4, 38 at stride 8.
  EXPECT_EQ(search.levelsFor(505), 3);  // 64 at stride 8.
  EXPECT_EQ(search.levelsFor(5000), 3);  // Never more than mrs/levels.
  MrsParams fewer;
  fewer.min_coarse_frames = 10;
  fewer.levels = 5;
  EXPECT_EQ(MrsSearch(SequenceParams{}, fewer).levelsFor(100), 3);  // 13 cells at stride 8, 7 at 16.
}

TEST(MrsSearch, RecoversThePlantedAlignmentOfGlobalQueries) {
  const auto& route = standardRoute();
  const auto matcher = makeMatcher("mrs", globalSearchParams());
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

TEST(MrsSearch, FindsACopyOfTheReferenceAwayFromItsEnds) {
  const auto& route = standardRoute();
  const auto mrs = makeMatcher("mrs", Parameters{});
  for (int end : {199, 420}) {
    EXPECT_EQ(mrs->match(route.reference.view(), route.reference.view(end - 159, end + 1)).reference_index, end);
  }
}

TEST(MrsSearch, FindsACopyOfTheReferenceAtEveryEnd) {
  // An exact copy has a needle-sharp cost at finer levels: only the true end matches. Resampling
  // must not jitter the best particle away from it, and the particles must settle after a
  // resampling before the heaviest go on to the next level (both once placed N = 160 copies
  // 10 frames early, e.g. 464 -> 454).

  const auto& route = standardRoute();
  const auto mrs = makeMatcher("mrs", Parameters{});
  for (int end = 170; end < 590; end += 7) {
    EXPECT_EQ(mrs->match(route.reference.view(), route.reference.view(end - 159, end + 1)).reference_index, end)
        << "end " << end;
  }
}

TEST(MrsSearch, FindsASequenceEndingAtTheNewestReferenceFrame) {
  // Cells of stride s end at frames J * s. With 600 reference frames the last complete stride-4
  // cell ends at 596; a partial cell ending at 600 makes frames 597..599 reachable (without it a
  // 160-frame copy ending at 599 was placed at 586).

  const auto& route = standardRoute();
  const auto mrs = makeMatcher("mrs", Parameters{});
  EXPECT_EQ(mrs->match(route.reference.view(), route.reference.view(440, 600)).reference_index, 599);
}

TEST(MrsSearch, CentredAlignmentReportsTheMiddleFrame) {
  const auto& route = standardRoute();
  Parameters params = globalSearchParams();
  params.sequence.alignment = WindowAlignment::kCentred;
  const auto matcher = makeMatcher("mrs", params);
  for (int start : {20, 150, 250}) {
    const int length = 128;
    const Match match = matcher->match(route.reference.view(), route.query.view(start, start + length));
    const int truth = route.query_to_reference[static_cast<std::size_t>(start + length / 2)];
    EXPECT_TRUE(within(match.reference_index, truth, 3))
        << "start " << start << ": got " << match.reference_index << ", truth " << truth;
  }
  EXPECT_EQ(matcher->match(route.reference.view(), route.reference.view(300, 428)).reference_index, 364);
}

TEST(MrsSearch, MatchEveryFrameGetsMostFramesRightAndSkipsIncompleteSequences) {
  const auto& route = standardRoute();
  const auto matcher = makeMatcher("mrs", Parameters{});  // sequence_length 10
  const SequenceView query = route.query.view(0, 200);
  const std::vector<Match> matches = matcher->matchEveryFrame(route.reference.view(), query);
  ASSERT_EQ(matches.size(), 200U);
  for (int frame = 0; frame < 9; ++frame) EXPECT_EQ(matches[static_cast<std::size_t>(frame)].reference_index, -1);
  int correct = 0;
  for (int frame = 9; frame < 200; ++frame) {
    correct += within(matches[static_cast<std::size_t>(frame)].reference_index,
                      route.query_to_reference[static_cast<std::size_t>(frame)], 3)
                   ? 1
                   : 0;
  }
  EXPECT_GE(correct, 0.9 * 191) << correct << " of 191";
}

TEST(MrsSearch, CentredMatchEveryFrameLocalisesTheFrameItself) {
  const auto& route = standardRoute();
  Parameters params;
  params.sequence.alignment = WindowAlignment::kCentred;
  const auto matcher = makeMatcher("mrs", params);
  // Identical frames 100..139: frame i of the query is reference frame 100 + i; frames without a
  // full centred sequence of 10 (i < 5, i > 35) get -1.
  const std::vector<Match> matches = matcher->matchEveryFrame(route.reference.view(), route.reference.view(100, 140));
  for (int frame : {0, 4, 36, 39}) EXPECT_EQ(matches[static_cast<std::size_t>(frame)].reference_index, -1) << frame;
  // Per-frame sequences are rows [i - 5, i + 4]; match() must anchor them at row 10 / 2 = frame i.
  for (int frame = 5; frame <= 35; ++frame) {
    EXPECT_EQ(matches[static_cast<std::size_t>(frame)].reference_index, 100 + frame) << "frame " << frame;
  }
}

TEST(MrsSearch, KeptPyramidGivesTheSameAnswer) {
  const auto& route = standardRoute();
  const Parameters params = globalSearchParams();
  const DescriptorSequence with_pyramid = withKeptCells(route.reference, params.mrs);
  const auto matcher = makeMatcher("mrs", params);
  for (int start : {0, 120, 200}) {
    const SequenceView query = route.query.view(start, start + 200);
    const Match plain = matcher->match(route.reference.view(), query);
    const Match kept = matcher->match(with_pyramid.view(), query);
    expectIdentical(plain, kept);
    EXPECT_TRUE(within(kept.reference_index, route.query_to_reference[static_cast<std::size_t>(start + 199)], 3));
    // A prefix of the map (as a recent_frames query searches) uses the kept cells it contains and
    // pools its last, partial cell.
    expectIdentical(matcher->match(route.reference.view(0, 597), query),
                    matcher->match(with_pyramid.view(0, 597), query));
  }
}

TEST(MrsSearch, SameSeedGivesIdenticalMatches) {
  const auto& route = standardRoute();
  const auto matcher = makeMatcher("mrs", globalSearchParams());
  const SequenceView query = route.query.view(30, 230);
  const Match first = matcher->match(route.reference.view(), query);
  expectIdentical(first, matcher->match(route.reference.view(), query));
  expectIdentical(first, makeMatcher("mrs", globalSearchParams())->match(route.reference.view(), query));
  EXPECT_GT(first.comparisons, 0);
}

TEST(MrsSearch, ThreadCountDoesNotChangeTheMatch) {
  const auto& route = longRoute();
  const Parameters params = globalSearchParams();
  const DescriptorSequence with_pyramid = withKeptCells(route.reference, params.mrs);
  const auto matcher = makeMatcher("mrs", params);
  const int threads = cv::getNumThreads();
  const SequenceView query = route.query.view(0, 300);
  // The coarsest level's matrix and trajectory sums are split over threads; their results, and so
  // the particles' path, must not depend on the split. With cells pooled per query and kept ones.
  for (const DescriptorSequence* reference : std::vector<const DescriptorSequence*>{&route.reference, &with_pyramid}) {
    cv::setNumThreads(1);
    const Match serial = matcher->match(reference->view(), query);
    cv::setNumThreads(4);
    const Match parallel = matcher->match(reference->view(), query);
    cv::setNumThreads(threads);
    expectIdentical(serial, parallel);
  }
}

TEST(MrsSearch, MakesFarFewerComparisonsThanSeqSlamOnALongReference) {
  const auto& route = longRoute();
  const Parameters params = globalSearchParams();
  const auto mrs = makeMatcher("mrs", params);
  const auto seqslam = makeMatcher("seqslam", params);
  const SequenceView query = route.query.view(0, 300);
  const int truth = route.query_to_reference[299];
  const Match fast = mrs->match(route.reference.view(), query);
  const Match brute = seqslam->match(route.reference.view(), query);
  EXPECT_TRUE(within(brute.reference_index, truth, 3)) << brute.reference_index << " vs " << truth;
  EXPECT_TRUE(within(fast.reference_index, truth, 3)) << fast.reference_index << " vs " << truth;
  EXPECT_EQ(brute.comparisons, 300LL * 2400);
  EXPECT_LT(fast.comparisons * 20, brute.comparisons)
      << "MRS " << fast.comparisons << " comparisons, SeqSLAM " << brute.comparisons;
}

TEST(MrsSearch, BadInputsThrowWithAClearMessage) {
  const auto& route = standardRoute();
  const auto matcher = makeMatcher("mrs", Parameters{});
  const std::string too_short =
      invalidArgumentMessage([&] { matcher->match(route.reference.view(), route.query.view(0, 1)); });
  EXPECT_NE(too_short.find("at least 2 frames"), std::string::npos) << too_short;
  const std::string too_long =
      invalidArgumentMessage([&] { matcher->match(route.reference.view(0, 100), route.query.view(0, 101)); });
  EXPECT_NE(too_long.find("longer than the reference"), std::string::npos) << too_long;
  DescriptorSequence small(64);
  for (int i = 0; i < 3; ++i) small.append(cv::Mat(1, 64, CV_8U, cv::Scalar(i)));
  const std::string sizes = invalidArgumentMessage([&] { matcher->match(route.reference.view(), small.view()); });
  EXPECT_NE(sizes.find("64 bytes"), std::string::npos) << sizes;

  // Pixel pooling that does not divide the descriptor: named when matching, and by makeMatcher's
  // caller through Parameters::validate().
  SequenceParams sequence;
  MrsParams mrs;
  mrs.pixel_pooling = 3;
  const MrsSearch odd_pooling(sequence, mrs);
  const std::string pooling =
      invalidArgumentMessage([&] { odd_pooling.match(route.reference.view(), route.query.view(0, 100)); });
  EXPECT_NE(pooling.find("mrs/pixel_pooling"), std::string::npos) << pooling;

  Parameters bad;
  bad.mrs.tau = 0.0;
  const std::string tau = invalidArgumentMessage([&] { makeMatcher("mrs", bad); });
  EXPECT_NE(tau.find("mrs/tau"), std::string::npos) << tau;
}

TEST(MrsSearch, ShortQueriesUseFullResolutionAndStillMatch) {
  const auto& route = standardRoute();
  const auto matcher = makeMatcher("mrs", Parameters{});
  // 20 frames: levelsFor gives 0, a search at stride 1.
  const Match match = matcher->match(route.reference.view(), route.query.view(250, 270));
  EXPECT_TRUE(within(match.reference_index, route.query_to_reference[269], 3))
      << match.reference_index << " vs " << route.query_to_reference[269];
}

}  // namespace
}  // namespace mrs_vpr
