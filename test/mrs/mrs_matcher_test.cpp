#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "mrs_vpr/acceptance.hpp"
#include "mrs_vpr/mrs_matcher.hpp"
#include "mrs_vpr/parameters.hpp"
#include "mrs_vpr/seqslam_matcher.hpp"
#include "mrs_vpr/trajectory_search.hpp"
#include "mrs_vpr/sequence_matcher.hpp"
#include "support/route_fixture.hpp"
#include "support/error_message.hpp"

namespace mrs_vpr {
namespace {

using testing_support::invalidArgumentMessage;
using testing_support::longRoute;
using testing_support::globalSearchParams;
using testing_support::routeDescriptor;
using testing_support::routeParameters;
using testing_support::standardRoute;
using testing_support::within;

void expectIdentical(const Match& a, const Match& b) {
  EXPECT_EQ(a.reference_index, b.reference_index);
  EXPECT_EQ(a.score, b.score);
  EXPECT_EQ(a.confidence, b.confidence);
  EXPECT_EQ(a.sequence_difference, b.sequence_difference);
  EXPECT_EQ(a.comparisons, b.comparisons);
}

/// A copy of `reference` that keeps the coarse cells MRS reads, as the node's map does.
DescriptorSequence withKeptCells(const DescriptorSequence& reference, const MrsParams& mrs) {
  DescriptorSequence kept = reference;
  kept.keepCoarseCells(mrs.levels, routeDescriptor());
  return kept;
}

TEST(MrsMatcher, LevelsForKeepsEnoughCoarseFrames) {
  const MrsMatcher search(SequenceParams{}, MrsParams{});  // levels 3, min_coarse_frames 64
  constexpr int kLargeMap = 100000;
  EXPECT_EQ(search.levelsFor(10, kLargeMap), 0);
  EXPECT_EQ(search.levelsFor(126, kLargeMap), 0);  // 63 cells at stride 2: too few ...
  EXPECT_EQ(search.levelsFor(127, kLargeMap), 1);  // ... 64 cells at stride 2 (frames 0, 2, ..., 126).
  EXPECT_EQ(search.levelsFor(200, kLargeMap), 1);  // 50 cells at stride 4: too few.
  EXPECT_EQ(search.levelsFor(252, kLargeMap), 1);  // 63 cells at stride 4 ...
  EXPECT_EQ(search.levelsFor(253, kLargeMap), 2);  // ... 64.
  EXPECT_EQ(search.levelsFor(300, kLargeMap), 2);  // 75 at stride 4, 38 at stride 8.
  EXPECT_EQ(search.levelsFor(505, kLargeMap), 3);  // 64 at stride 8.
  EXPECT_EQ(search.levelsFor(5000, kLargeMap), 3);  // Never more than mrs/levels.
  MrsParams fewer;
  fewer.min_coarse_frames = 10;
  fewer.levels = 5;
  EXPECT_EQ(MrsMatcher(SequenceParams{}, fewer).levelsFor(100, kLargeMap), 3);  // 13 cells at stride 8, 7 at 16.
}

TEST(MrsMatcher, LevelsForKeepsEnoughRivalEndsOnTheCoarsestLevel) {
  // The confidence is read on the coarsest level's ends, so a small map gets a finer one. At N = 300
  // and stride 4 the trajectories of the slowest velocity end at cells 59 (frame 236) and beyond,
  // and the answer's window takes 11 cells: 100 rivals need cells 59..169, a map of 674 frames.
  SequenceParams causal;  // Centred trajectories reach past the answer and need other ends.
  causal.alignment = WindowAlignment::kCausal;
  const MrsMatcher search(causal, MrsParams{});
  EXPECT_EQ(search.levelsFor(300, 674), 2);
  EXPECT_EQ(search.levelsFor(300, 673), 1);  // 99 rivals at stride 4; stride 2 has enough.
  EXPECT_EQ(search.levelsFor(300, 300), 0);  // Not enough at any stride: the brute force's search.
}

TEST(MrsMatcher, FindsACopyOfTheReferenceAwayFromItsEnds) {
  const auto& route = standardRoute();
  const auto mrs = makeMatcher("mrs", routeParameters());
  for (int end : {199, 420}) {
    EXPECT_EQ(mrs->match(route.reference.view(), route.reference.view(end - 159, end + 1)).reference_index, end);
  }
}

TEST(MrsMatcher, FindsACopyOfTheReferenceAtEveryEnd) {
  // An exact copy has a needle-sharp cost at finer levels: only the true end matches. Resampling
  // must not jitter the best particle away from it, and the particles must settle after a
  // resampling before the heaviest go on to the next level (both once placed N = 160 copies
  // 10 frames early, e.g. 464 -> 454).

  const auto& route = standardRoute();
  const auto mrs = makeMatcher("mrs", routeParameters());
  for (int end = 170; end < 590; end += 7) {
    EXPECT_EQ(mrs->match(route.reference.view(), route.reference.view(end - 159, end + 1)).reference_index, end)
        << "end " << end;
  }
}

TEST(MrsMatcher, FindsASequenceEndingAtTheNewestReferenceFrame) {
  // Cells of stride s end at frames J * s. With 600 reference frames the last complete stride-4
  // cell ends at 596; a partial cell ending at 600 makes frames 597..599 reachable (without it a
  // 160-frame copy ending at 599 was placed at 586).

  const auto& route = standardRoute();
  const auto mrs = makeMatcher("mrs", routeParameters());
  EXPECT_EQ(mrs->match(route.reference.view(), route.reference.view(440, 600)).reference_index, 599);
}

TEST(MrsMatcher, CentredMatchEveryFrameLocalisesTheFrameItself) {
  const auto& route = standardRoute();
  Parameters params = routeParameters();
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

TEST(MrsMatcher, KeptPyramidGivesTheSameAnswer) {
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

TEST(MrsMatcher, AnswersDoNotDependOnTheNumberOfThreads) {
  // The hypotheses settle in parallel and every dense level is split between threads: the answer,
  // its confidence and the work counted must be the same with one thread and with several.
  const auto& route = standardRoute();
  const auto matcher = makeMatcher("mrs", globalSearchParams());
  const int threads = cv::getNumThreads();
  for (const int length : {200, 300}) {
    const SequenceView query = route.query.view(0, length);
    cv::setNumThreads(1);
    const Match single = matcher->match(route.reference.view(), query);
    cv::setNumThreads(4);
    ASSERT_EQ(cv::getNumThreads(), 4) << "OpenCV runs one thread only here: nothing is split";
    const Match several = matcher->match(route.reference.view(), query);
    cv::setNumThreads(threads);
    SCOPED_TRACE(length);
    ASSERT_GE(single.reference_index, 0);
    expectIdentical(single, several);
  }
}

TEST(MrsMatcher, SameSeedGivesIdenticalMatches) {
  const auto& route = standardRoute();
  const auto matcher = makeMatcher("mrs", globalSearchParams());
  const SequenceView query = route.query.view(30, 230);
  const Match first = matcher->match(route.reference.view(), query);
  expectIdentical(first, matcher->match(route.reference.view(), query));
  expectIdentical(first, makeMatcher("mrs", globalSearchParams())->match(route.reference.view(), query));
  EXPECT_GT(first.comparisons, 0);
}

TEST(MrsMatcher, ThreadCountDoesNotChangeTheMatch) {
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
    ASSERT_EQ(cv::getNumThreads(), 4) << "OpenCV runs one thread only here: nothing is split";
    const Match parallel = matcher->match(reference->view(), query);
    cv::setNumThreads(threads);
    ASSERT_GE(serial.reference_index, 0);
    expectIdentical(serial, parallel);
  }
}

TEST(MrsMatcher, MakesFarFewerComparisonsThanSeqSlamOnALongReference) {
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

TEST(MrsMatcher, BadInputsThrowWithAClearMessage) {
  const auto& route = standardRoute();
  const auto matcher = makeMatcher("mrs", routeParameters());
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

  // Descriptors of another geometry than the matcher's: its coarse cells cannot be computed, and
  // the message names both sizes. Without a coarser level (short sequences) the geometry is unused.
  DescriptorParams other = routeDescriptor();
  other.image_width = 32;
  const MrsMatcher other_geometry(SequenceParams{}, MrsParams{}, other);
  const std::string geometry =
      invalidArgumentMessage([&] { other_geometry.match(route.reference.view(), route.query.view(0, 200)); });
  EXPECT_NE(geometry.find("thumbnail (32 x 32, patches of 8 px) front end, 1024 bytes, got 2048"), std::string::npos)
      << geometry;
  EXPECT_NO_THROW(other_geometry.match(route.reference.view(), route.query.view(0, 20)));

  Parameters bad;
  bad.mrs.tau = 0.0;
  const std::string tau = invalidArgumentMessage([&] { makeMatcher("mrs", bad); });
  EXPECT_NE(tau.find("mrs/tau"), std::string::npos) << tau;
}

TEST(MrsMatcher, ShortQueriesUseFullResolutionAndStillMatch) {
  const auto& route = standardRoute();
  const auto matcher = makeMatcher("mrs", routeParameters());
  // 20 frames: levelsFor gives 0, a search at stride 1.
  const Match match = matcher->match(route.reference.view(), route.query.view(250, 270));
  EXPECT_TRUE(within(match.reference_index, route.query_to_reference[269], 3))
      << match.reference_index << " vs " << route.query_to_reference[269];
}

/// Rank of `truth` among reference frames `minima` (cells ending within a cell of it), -1 if absent.
int rankOf(const std::vector<int>& minima, int truth, int stride) {
  for (std::size_t i = 0; i < minima.size(); ++i) {
    if (within(minima[i], truth, stride + 1)) return static_cast<int>(i);
  }
  return -1;
}

TEST(MrsMatcher, DescendsTwoLevelsOnALongReference) {
  // The standard route is too short for two levels at N = 300 (too few rival ends at stride 4).
  const auto& route = longRoute();
  const Parameters params = globalSearchParams();
  const MrsMatcher search(params.sequence, params.mrs, params.descriptor);
  ASSERT_EQ(search.levelsFor(300, route.reference.size()), 2);
  std::vector<MrsLevelTrace> trace;
  const Match match = search.match(route.reference.view(), route.query.view(0, 300), &trace);
  ASSERT_EQ(trace.size(), 3U);
  EXPECT_EQ(trace[0].stride, 4);
  EXPECT_EQ(trace[1].stride, 2);
  EXPECT_EQ(trace[2].stride, 1);
  const int truth = route.query_to_reference[299];
  EXPECT_TRUE(within(match.reference_index, truth, 3)) << match.reference_index << " vs " << truth;
  EXPECT_TRUE(match.accepted) << "confidence " << match.confidence;
  // The rivals are the coarsest level's cells outside the answer's window.
  EXPECT_GE(match.rivals, kMinRivalEnds);
  EXPECT_LT(match.rivals, route.reference.size() / 4);
}

TEST(MrsMatcher, TraceRecordsEveryLevelCoarsestFirstWithDistinctTableMinima) {
  const auto& route = standardRoute();
  const Parameters params = globalSearchParams();
  const MrsMatcher search(params.sequence, params.mrs, params.descriptor);
  for (int length : {150, 200, 300}) {
    const int levels = search.levelsFor(length, route.reference.size());
    ASSERT_GT(levels, 0) << "N = " << length;
    // The separation of the coarse minima, in cells of the coarsest level (see hypothesisSeparation).
    const int separation = std::max(2 * params.mrs.index_shift + 1, params.sequence.match_exclusion >> levels);
    for (int start : {0, 50, 99}) {
      const int end = start + length - 1;
      if (end >= route.query.size()) continue;
      const int truth = route.query_to_reference[static_cast<std::size_t>(end)];
      const SequenceView query = route.query.view(start, end + 1);
      std::vector<MrsLevelTrace> trace;
      const Match traced = search.match(route.reference.view(), query, &trace);
      const std::string where = "N = " + std::to_string(length) + ", start " + std::to_string(start);

      // One entry per level, coarsest first, the stride halving down to full resolution.
      ASSERT_EQ(static_cast<int>(trace.size()), levels + 1) << where;
      for (int level = 0; level <= levels; ++level) {
        EXPECT_EQ(trace[static_cast<std::size_t>(level)].stride, 1 << (levels - level)) << where;
      }

      // The coarse table's minima are cell ends, distinct places, and the truth is among the first.
      const MrsLevelTrace& coarsest = trace.front();
      ASSERT_FALSE(coarsest.table_minima.empty()) << where;
      EXPECT_LE(static_cast<int>(coarsest.table_minima.size()), MrsLevelTrace::kTracedMinima) << where;
      for (std::size_t a = 0; a < coarsest.table_minima.size(); ++a) {
        EXPECT_EQ(coarsest.table_minima[a] % coarsest.stride, 0) << where;
        for (std::size_t b = 0; b < a; ++b) {
          EXPECT_GT(std::abs(coarsest.table_minima[a] - coarsest.table_minima[b]), separation * coarsest.stride)
              << where << ": minima " << coarsest.table_minima[b] << " and " << coarsest.table_minima[a];
        }
      }
      const int rank = rankOf(coarsest.table_minima, truth, coarsest.stride);
      EXPECT_GE(rank, 0) << where << ": truth " << truth;
      EXPECT_LE(rank, 2) << where << ": truth " << truth;
      // Only the coarsest level ranks the whole table.
      for (std::size_t level = 1; level < trace.size(); ++level) EXPECT_TRUE(trace[level].table_minima.empty());

      // Below the coarsest level: at most mrs/hypotheses places; below the one comparing them, only the winner.
      ASSERT_GE(trace.size(), 2U);
      EXPECT_GE(trace[1].candidates.size(), 1U) << where;
      EXPECT_LE(static_cast<int>(trace[1].candidates.size()), params.mrs.hypotheses) << where;
      for (std::size_t level = 2; level < trace.size(); ++level) EXPECT_EQ(trace[level].candidates.size(), 1U) << where;
      // The finest level's best hypothesis is the answer.
      EXPECT_EQ(trace.back().candidates.front(), traced.reference_index) << where;

      // Tracing only observes: the same answer as without it.
      const Match plain = search.match(route.reference.view(), query);
      expectIdentical(plain, traced);
      EXPECT_EQ(plain.accepted, traced.accepted) << where;
      EXPECT_TRUE(within(traced.reference_index, truth, 3))
          << where << ": " << traced.reference_index << " vs " << truth;
    }
  }
}

TEST(MrsMatcher, HypothesesCountIsRespectedBelowTheCoarsestLevel) {
  const auto& route = standardRoute();
  Parameters params = globalSearchParams();
  const SequenceView query = route.query.view(40, 190);
  for (int hypotheses : {2, 3, 8}) {
    params.mrs.hypotheses = hypotheses;
    std::vector<MrsLevelTrace> trace;
    MrsMatcher(params.sequence, params.mrs, params.descriptor).match(route.reference.view(), query, &trace);
    ASSERT_EQ(trace.size(), 2U);
    EXPECT_GE(trace[1].candidates.size(), 1U) << hypotheses;
    EXPECT_LE(static_cast<int>(trace[1].candidates.size()), hypotheses) << hypotheses;
  }
}

TEST(MrsMatcher, TwoOrEightHypothesesBothFindThePlantedTruthOnTheRoute) {
  // On the generated route the truth is the coarse table's first minimum, so the fewest hypotheses
  // already suffice; more must not lose it (nor change how sure the answer is).
  const auto& route = standardRoute();
  Parameters one = globalSearchParams();
  one.mrs.hypotheses = 2;
  Parameters eight = globalSearchParams();
  eight.mrs.hypotheses = 8;
  const auto single = makeMatcher("mrs", one);
  const auto several = makeMatcher("mrs", eight);
  for (int length : {150, 300}) {
    for (int start : {0, 60, 99}) {
      const int end = start + length - 1;
      const int truth = route.query_to_reference[static_cast<std::size_t>(end)];
      const SequenceView query = route.query.view(start, end + 1);
      const Match a = single->match(route.reference.view(), query);
      const Match b = several->match(route.reference.view(), query);
      EXPECT_TRUE(within(a.reference_index, truth, 3))
          << "N = " << length << ", start " << start << ": " << a.reference_index;
      EXPECT_TRUE(within(b.reference_index, truth, 3))
          << "N = " << length << ", start " << start << ": " << b.reference_index;
      EXPECT_TRUE(a.accepted);
      EXPECT_TRUE(b.accepted);
    }
  }
}

/// The route's reference with frames [at, at + count) replaced by the query's frames
/// [from, from + count), each pair (from + 2i, from + 2i + 1) swapped: averaged over the pair (a
/// stride-2 cell) the copy is the query itself, frame by frame it is never the right frame.
DescriptorSequence withPairSwappedCopy(const DescriptorSequence& reference, const DescriptorSequence& query, int from,
                                       int at, int count) {
  DescriptorSequence result(reference.descriptorSize());
  for (int frame = 0; frame < reference.size(); ++frame) {
    int source_frame = frame;
    const DescriptorSequence* source = &reference;
    if (frame >= at && frame < at + count) {
      const int i = frame - at;
      source_frame = from + (i % 2 == 0 ? i + 1 : i - 1);
      source = &query;
    }
    result.append(source->descriptorRow(source_frame), reference.stamp(frame));
  }
  return result;
}

TEST(MrsMatcher, MoreHypothesesRecoverATruthTheCoarseTableRanksSecond) {
  // A decoy that looks exactly like the query at stride 2 but wrong at every single frame: the
  // coarse table ranks it first, the truth below it. Only a search that carries more than one coarse
  // minimum down to full resolution can find the truth.
  const auto& route = standardRoute();
  const int start = 250;
  const int length = 150;  // One level: stride 2, then full resolution.
  const int end = start + length - 1;
  const int truth = route.query_to_reference[static_cast<std::size_t>(end)];
  ASSERT_GT(truth, 300);
  // Odd: the query's pairs (start + 2i, start + 2i + 1), whose last frame is the anchor, then fill
  // the reference's stride-2 cells (2J - 1, 2J) exactly.
  const int at = 41;
  const int decoy_end = at + length - 1;
  const DescriptorSequence reference = withPairSwappedCopy(route.reference, route.query, start, at, length);
  const SequenceView query = route.query.view(start, end + 1);

  Parameters params = globalSearchParams();
  ASSERT_EQ(MrsMatcher(params.sequence, params.mrs, params.descriptor).levelsFor(length, reference.size()), 1);
  params.mrs.hypotheses = 8;
  std::vector<MrsLevelTrace> trace;
  const Match several =
      MrsMatcher(params.sequence, params.mrs, params.descriptor).match(reference.view(), query, &trace);
  ASSERT_EQ(trace.size(), 2U);
  EXPECT_EQ(rankOf(trace.front().table_minima, decoy_end, 2), 0) << "the decoy is not the coarse minimum";
  EXPECT_EQ(rankOf(trace.front().table_minima, truth, 2), 1) << "truth " << truth;
  EXPECT_TRUE(within(several.reference_index, truth, 3)) << several.reference_index << " vs " << truth;

  // A single hypothesis would go down alone: it answered the decoy and accepted it (confidence
  // 4.75, measured), with nothing at a finer level to check it against. So there are at least two.
  params.mrs.hypotheses = 1;
  EXPECT_THROW(params.mrs.validate(), std::invalid_argument);

  // The brute force, which sees every frame, agrees with the search that kept the truth.
  EXPECT_TRUE(within(makeMatcher("seqslam", params)->match(reference.view(), query).reference_index, truth, 3));
  // The confidence is read on the coarse table, where the decoy beats the truth: the right answer is
  // reported but not claimed as a loop closure.
  EXPECT_FALSE(several.accepted) << "confidence " << several.confidence;
}

TEST(MrsMatcher, PerFrameWithoutCoarserLevelsEqualsTheBruteForceFrameByFrame) {
  // Sequence lengths that leave no coarser level (levelsFor(N) == 0, e.g. the default 10 and 40):
  // MRS must give the brute force's answers frame by frame, and its own search of each sequence the
  // same place and confidence.
  const auto& route = standardRoute();
  const SequenceView query = route.query.view(150, 250);
  for (int length : {10, 40}) {
    for (WindowAlignment alignment : {WindowAlignment::kCausal, WindowAlignment::kCentred}) {
      Parameters params = routeParameters();
      params.sequence.sequence_length = length;
      params.sequence.alignment = alignment;
      const MrsMatcher mrs(params.sequence, params.mrs, params.descriptor);
      ASSERT_EQ(mrs.levelsFor(length, route.reference.size()), 0);
      const std::vector<Match> fast = mrs.matchEveryFrame(route.reference.view(), query);
      const std::vector<Match> brute = SeqSlamMatcher(params.sequence).matchEveryFrame(route.reference.view(), query);
      ASSERT_EQ(fast.size(), brute.size());
      const std::string where =
          "N = " + std::to_string(length) + (alignment == WindowAlignment::kCausal ? " causal" : " centred");
      int found = 0;
      int accepted = 0;
      for (std::size_t frame = 0; frame < fast.size(); ++frame) {
        EXPECT_EQ(fast[frame].reference_index, brute[frame].reference_index) << where << ", frame " << frame;
        EXPECT_EQ(fast[frame].confidence, brute[frame].confidence) << where << ", frame " << frame;
        EXPECT_EQ(fast[frame].accepted, brute[frame].accepted) << where << ", frame " << frame;
        found += fast[frame].reference_index >= 0 ? 1 : 0;
        accepted += fast[frame].accepted ? 1 : 0;
      }
      EXPECT_EQ(found, query.count - length + 1) << where;  // Every complete sequence is answered.
      // At N = 40 the comparison covers accepted answers too, not only rejected ones.
      if (length == 40) EXPECT_GT(accepted, 0) << where;
      for (int frame : {length, query.count / 2, query.count - length / 2 - 1}) {
        const SequenceRows rows = sequenceRowsFor(frame, params.sequence);
        const Match single = mrs.match(route.reference.view(), query.slice(rows.first, rows.last + 1));
        const Match& every = fast[static_cast<std::size_t>(frame)];
        EXPECT_EQ(single.reference_index, every.reference_index) << where << ", frame " << frame;
        EXPECT_FLOAT_EQ(single.confidence, every.confidence) << where << ", frame " << frame;
        EXPECT_EQ(single.accepted, every.accepted) << where << ", frame " << frame;
      }
    }
  }
}

}  // namespace
}  // namespace mrs_vpr
