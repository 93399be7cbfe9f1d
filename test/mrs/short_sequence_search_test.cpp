#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "mrs_vpr/acceptance.hpp"
#include "mrs_vpr/contrast_enhancement.hpp"
#include "mrs_vpr/difference_matrix.hpp"
#include "mrs_vpr/mrs/chosen_end_costs.hpp"
#include "mrs_vpr/mrs/compact_cells.hpp"
#include "mrs_vpr/mrs/short_sequence_search.hpp"
#include "mrs_vpr/mrs_matcher.hpp"
#include "mrs_vpr/seqslam_matcher.hpp"
#include "mrs_vpr/trajectory_search.hpp"
#include "support/route_fixture.hpp"

namespace mrs_vpr {
namespace {

using testing_support::routeDescriptor;
using testing_support::routeParameters;
using testing_support::standardRoute;

/// The route's map with the compact cells the node's map keeps.
const DescriptorSequence& keptMap() {
  static const DescriptorSequence map = [] {
    DescriptorSequence kept = standardRoute().reference;
    kept.keepCoarseCells(MrsParams{}.levels, routeDescriptor());
    return kept;
  }();
  return map;
}

// Ends in the middle and at both edges of the map, causal and centred: the brute force's costs.
TEST(ChosenEndCosts, EqualTheBruteForceCostsOfTheSameEnds) {
  const DescriptorSequence& map = keptMap();
  const SequenceView query = standardRoute().query.view(100, 120);
  const std::vector<double> speeds = velocities(SequenceParams{});
  for (WindowAlignment alignment : {WindowAlignment::kCausal, WindowAlignment::kCentred}) {
    const SequenceRows rows = wholeSequenceRows(query.count, alignment);
    const AnchorCosts whole =
        costsByAnchor(enhanceContrast(computeDifferenceMatrix(query, map.view()), 10), rows, speeds);
    const ChosenEndCosts chosen(map.view(), query, rows, speeds, 10);
    for (const auto& [begin, end] : std::vector<std::pair<int, int>>{{0, 30}, {290, 291}, {300, 340}, {580, 600}}) {
      std::vector<float> cost(static_cast<std::size_t>(end - begin));
      std::vector<float> velocity(cost.size());
      EXPECT_GT(chosen.compute(begin, end, cost.data(), velocity.data()), 0);
      for (int j = begin; j < end; ++j) {
        const auto at = static_cast<std::size_t>(j);
        const std::string where = toString(alignment) + ", end " + std::to_string(j);
        if (std::isinf(whole.cost[at])) {
          EXPECT_TRUE(std::isinf(cost[at - begin])) << where;  // No trajectory fits, in both.
          continue;
        }
        EXPECT_EQ(cost[at - begin], whole.cost[at]) << where;  // Pieces of rows enhance as whole rows.
        EXPECT_EQ(velocity[at - begin], whole.velocity[at]) << where;
      }
    }
  }
}

/// Answers of the short-sequence search and of the brute force to queries of 10, 20 and 50 frames.
template <typename Check>
void compareWithBruteForce(int hypotheses, const Check& check) {
  const Parameters params = routeParameters();
  const SeqSlamMatcher brute(params.sequence);
  const auto compact = makeCompactCells(params.descriptor);
  for (int length : {10, 20, 50}) {
    for (int start : {0, 90, 200, 333}) {
      const SequenceView query = standardRoute().query.view(start, start + length);
      MrsLevelTrace trace;
      const Match found = searchShortSequence(keptMap().view(), query, params.sequence, *compact, hypotheses, &trace);
      check(found, brute.match(keptMap().view(), query), trace,
            "length " + std::to_string(length) + ", start " + std::to_string(start));
    }
  }
}

// With the default hypotheses the first pass keeps the brute force's answer and its rival among
// them: the same end, velocity, cost and rival, so the same score; the rivals are counted on the
// same ends; the confidence's spread is read on the first pass's table.
TEST(ShortSequenceSearch, GivesTheBruteForceAnswerOnTheGeneratedRoute) {
  int compared = 0;
  compareWithBruteForce(kShortSearchHypotheses, [&](const Match& found, const Match& expected,
                                                         const MrsLevelTrace& trace, const std::string& where) {
    EXPECT_EQ(found.reference_index, expected.reference_index) << where;
    EXPECT_EQ(found.velocity, expected.velocity) << where;
    EXPECT_NEAR(found.sequence_difference, expected.sequence_difference, 1e-5F) << where;
    EXPECT_NEAR(found.score, expected.score, 1e-5F) << where;
    EXPECT_EQ(found.rivals, expected.rivals) << where;
    // Its spread is the larger of two estimates of the brute force's (the sample of the second holds
    // ~40 ends of this small map): near, never far above.
    EXPECT_NEAR(found.confidence, expected.confidence, 0.35F * expected.confidence + 0.1F) << where;
    EXPECT_LE(found.confidence, 1.1F * expected.confidence + 0.1F) << where;
    EXPECT_EQ(trace.stride, 1) << where;
    EXPECT_EQ(static_cast<int>(trace.candidates.size()), kShortSearchHypotheses) << where;
    ++compared;
  });
  EXPECT_EQ(compared, 12);
}

// With few hypotheses the answer is still the brute force's, but its rival (the least bad of many
// wrong places, where compact cells and descriptors rank alike only roughly) can be missed: the
// rival found is then never lower than the brute force's, so the score is never higher.
TEST(ShortSequenceSearch, FewHypothesesCanOnlyMissTheRival) {
  int missed = 0;
  compareWithBruteForce(4, [&](const Match& found, const Match& expected, const MrsLevelTrace& trace,
                               const std::string& where) {
    EXPECT_EQ(found.reference_index, expected.reference_index) << where;
    EXPECT_LE(found.score, expected.score + 1e-5F) << where;
    EXPECT_EQ(trace.candidates.size(), 4U) << where;
    if (found.score < expected.score - 1e-5F) ++missed;
  });
  EXPECT_GT(missed, 0);  // On this route, 3 of the 12 rivals lie beyond the first 4 minima.
}

// The map's kept cells and cells computed per query give the same answer.
TEST(ShortSequenceSearch, MapWithoutKeptCellsGivesTheSameAnswer) {
  const Parameters params = routeParameters();
  const auto compact = makeCompactCells(params.descriptor);
  const SequenceView query = standardRoute().query.view(150, 175);
  const Match kept = searchShortSequence(keptMap().view(), query, params.sequence, *compact, 8);
  const Match computed = searchShortSequence(standardRoute().reference.view(), query, params.sequence, *compact, 8);
  EXPECT_EQ(kept.reference_index, computed.reference_index);
  EXPECT_EQ(kept.confidence, computed.confidence);
  EXPECT_EQ(kept.comparisons, computed.comparisons);
}

// Only a large map pays for the first pass: on small ones MRS stays the brute force.
TEST(ShortSequenceSearch, PaysOnlyOnLargeMaps) {
  const Parameters params;
  for (int length : {10, 50, 100}) {
    EXPECT_FALSE(shortSearchPays(length, 5000, params.sequence, kShortSearchHypotheses)) << length;
    EXPECT_TRUE(shortSearchPays(length, 100000, params.sequence, kShortSearchHypotheses)) << length;
  }
  EXPECT_FALSE(shortSearchPays(1, 100000, params.sequence, kShortSearchHypotheses));
}

TEST(DescriptorSequence, KeepsEachFramesOwnCompactCell) {
  const DescriptorSequence& map = keptMap();
  const auto compact = makeCompactCells(routeDescriptor());
  const SequenceView cells = map.view().coarseCells(1, routeDescriptor());
  ASSERT_EQ(cells.count, map.size());
  std::vector<std::uint8_t> expected(static_cast<std::size_t>(compact->cellSize()));
  for (int frame : {0, 1, 299, map.size() - 1}) {
    compact->cell(standardRoute().reference.view(), frame, 1, expected.data());
    EXPECT_EQ(std::vector<std::uint8_t>(cells.frame(frame), cells.frame(frame) + cells.descriptor_size), expected)
        << frame;
  }
}

}  // namespace
}  // namespace mrs_vpr

namespace mrs_vpr {
namespace {

/// A thumbnail front end of 16 x 8 pixels: 128-byte descriptors, so that a map of tens of thousands
/// of frames, large enough for the first pass to pay, stays small.
DescriptorParams tinyThumbnail() {
  DescriptorParams params = routeDescriptor();
  params.image_width = 16;
  params.image_height = 8;
  return params;
}

// MrsMatcher takes the first pass on a large map: one traced level at stride 1, the brute force's
// answer, and far fewer full-descriptor comparisons.
TEST(MrsMatcher, ShortSequencesOnALargeMapTakeTheFirstPass) {
  const DescriptorParams front_end = tinyThumbnail();
  const int size = front_end.descriptorSize();
  constexpr int kFrames = 40000;
  DescriptorSequence map(size);
  map.keepCoarseCells(MrsParams{}.levels, front_end);
  map.reserve(kFrames);
  cv::RNG rng(7);
  cv::Mat frame(1, size, CV_8U);
  for (int i = 0; i < kFrames; ++i) {
    rng.fill(frame, cv::RNG::UNIFORM, 0, 256);
    map.append(frame);
  }
  // The query: frames 30000 .. 30009 of the map with noise.
  DescriptorSequence query(size);
  for (int i = 30000; i < 30010; ++i) {
    cv::Mat noisy;
    cv::Mat noise(1, size, CV_16S);
    rng.fill(noise, cv::RNG::NORMAL, 0, 20);
    map.descriptorRow(i).convertTo(noisy, CV_16S);
    noisy += noise;
    noisy.convertTo(noisy, CV_8U);
    query.append(noisy);
  }
  Parameters params = routeParameters();
  params.descriptor = front_end;
  ASSERT_TRUE(shortSearchPays(10, kFrames, params.sequence, kShortSearchHypotheses));
  const MrsMatcher mrs(params.sequence, params.mrs, front_end);
  std::vector<MrsLevelTrace> trace;
  const Match found = mrs.match(map.view(), query.view(), &trace);
  const Match expected = SeqSlamMatcher(params.sequence).match(map.view(), query.view());
  EXPECT_EQ(expected.reference_index, 30009);
  EXPECT_EQ(found.reference_index, expected.reference_index);
  EXPECT_TRUE(found.accepted);
  EXPECT_EQ(found.accepted, expected.accepted);
  ASSERT_EQ(trace.size(), 1U);
  EXPECT_EQ(trace[0].stride, 1);
  EXPECT_EQ(trace[0].table_minima.front(), 30009);  // The first pass's lowest minimum is the truth.
  // Compact cells count as their share of a descriptor comparison.
  EXPECT_LT(found.comparisons, expected.comparisons / 2);
  // Where the first pass pays, match() is matchByFirstPass().
  const Match first_pass = mrs.matchByFirstPass(map.view(), query.view(), nullptr);
  EXPECT_EQ(first_pass.reference_index, found.reference_index);
  EXPECT_EQ(first_pass.confidence, found.confidence);
  EXPECT_EQ(first_pass.accepted, found.accepted);
  EXPECT_EQ(first_pass.comparisons, found.comparisons);
}

// On a map too small for the first pass to pay, matchByFirstPass() still runs it: the search's own
// answer, accepted by the core's rule, and its one level traced.
TEST(MrsMatcher, MatchByFirstPassSearchesAnyMap) {
  const Parameters params = routeParameters();
  const SequenceView query = standardRoute().query.view(150, 175);
  ASSERT_FALSE(shortSearchPays(query.count, keptMap().size(), params.sequence, kShortSearchHypotheses));
  const MrsMatcher mrs(params.sequence, params.mrs, params.descriptor);
  std::vector<MrsLevelTrace> trace;
  const Match found = mrs.matchByFirstPass(keptMap().view(), query, &trace);
  Match expected = searchShortSequence(keptMap().view(), query, params.sequence,
                                       *makeCompactCells(params.descriptor), kShortSearchHypotheses);
  applyAcceptance(expected, params.sequence);
  EXPECT_EQ(found.reference_index, expected.reference_index);
  EXPECT_EQ(found.confidence, expected.confidence);
  EXPECT_EQ(found.accepted, expected.accepted);
  ASSERT_EQ(trace.size(), 1U);
  EXPECT_EQ(trace[0].stride, 1);
  EXPECT_EQ(static_cast<int>(trace[0].candidates.size()), kShortSearchHypotheses);
  // Its inputs are checked as match() checks them.
  EXPECT_THROW(mrs.matchByFirstPass(query, keptMap().view(), nullptr), std::invalid_argument);
}

/// Compact cells that see only the first half of a descriptor (its mean over the cell's frames).
class FirstHalfCells : public CompactCells {
 public:
  explicit FirstHalfCells(const DescriptorParams& geometry) : CompactCells(geometry) {}
  int cellSize() const override { return descriptorSize() / 2; }
  void project(const std::uint16_t* sums, int frames, std::uint8_t* cell) const override {
    for (int i = 0; i < cellSize(); ++i) cell[i] = static_cast<std::uint8_t>((sums[i] + frames / 2) / frames);
  }
};

// The full descriptors score every end within match_exclusion of the first pass's minimum, and then
// of the answer, the edges included. Each place holds the query's frames three times: alike in the
// half the cells see (the first pass's minimum); next to them, ending exactly match_exclusion after
// A's or before B's, alike throughout but noisy (the answer, which the first pass ranks far below the
// minimum, too near it to be a distinct minimum of its own); and beyond that, ending exactly
// match_exclusion further, noisier (the rival). One hypothesis leaves no other window to cover them.
TEST(ShortSequenceSearch, ScoresTheEndsExactlyMatchExclusionFromTheMinimumAndTheAnswer) {
  const DescriptorParams front_end = tinyThumbnail();
  const int size = front_end.descriptorSize();
  Parameters params = routeParameters();
  params.descriptor = front_end;
  const int exclusion = params.sequence.match_exclusion;
  const int length = 10;
  ASSERT_EQ(exclusion, length);  // the copies lie right next to each other
  cv::RNG rng(12);
  const auto randomFrame = [&] {
    cv::Mat frame(1, size, CV_8U);
    rng.fill(frame, cv::RNG::UNIFORM, 0, 256);
    return frame;
  };
  std::vector<cv::Mat> frames;
  for (int i = 0; i < 500; ++i) frames.push_back(randomFrame());
  const auto noisyCopy = [&](const cv::Mat& frame, double noise, int at) {
    cv::Mat values;
    cv::Mat deviation(1, size, CV_16S);
    rng.fill(deviation, cv::RNG::NORMAL, 0, noise);
    frame.convertTo(values, CV_16S);
    values += deviation;
    values.convertTo(frames[static_cast<std::size_t>(at)], CV_8U);
  };
  struct Place {
    int minimum;  ///< The last of the half-alike frames.
    int answer;   ///< The noisy copy's end.
    int rival;    ///< The noisier copy's end.
    DescriptorSequence query;
  };
  std::vector<Place> places;
  for (const int side : {1, -1}) {
    const int minimum = side > 0 ? 109 : 310;
    Place place{minimum, minimum + side * exclusion, minimum + 2 * side * exclusion, DescriptorSequence(size)};
    for (int i = 0; i < length; ++i) {
      const cv::Mat frame = randomFrame();
      place.query.append(frame);
      cv::Mat& half_alike = frames[static_cast<std::size_t>(place.minimum - length + 1 + i)];
      frame.colRange(0, size / 2).copyTo(half_alike.colRange(0, size / 2));
      noisyCopy(frame, 20.0, place.answer - length + 1 + i);
      noisyCopy(frame, 30.0, place.rival - length + 1 + i);
    }
    places.push_back(place);
  }
  DescriptorSequence map(size);
  for (const cv::Mat& frame : frames) map.append(frame);
  const FirstHalfCells cells(front_end);
  const SeqSlamMatcher brute(params.sequence);
  for (const Place& place : places) {
    const std::string where = "minimum " + std::to_string(place.minimum);
    // Not computed as one of the spread's sample either.
    ASSERT_NE(place.answer % kSpreadThinning, 0) << where;
    ASSERT_NE(place.rival % kSpreadThinning, 0) << where;
    MrsLevelTrace trace;
    const Match found = searchShortSequence(map.view(), place.query.view(), params.sequence, cells, 1, &trace);
    const Match expected = brute.match(map.view(), place.query.view());
    ASSERT_EQ(trace.candidates, std::vector<int>{place.minimum}) << where;
    EXPECT_EQ(expected.reference_index, place.answer) << where;
    EXPECT_EQ(found.reference_index, place.answer) << where;
    EXPECT_NEAR(found.sequence_difference, expected.sequence_difference, 1e-5F) << where;
    // The brute force's rival is the noisier copy, and so is the search's.
    const ChosenEndCosts chosen(map.view(), place.query.view(), wholeSequenceRows(length, params.sequence.alignment),
                                velocities(params.sequence), params.sequence.contrast_window);
    float rival_cost = 0.0F;
    float rival_velocity = 0.0F;
    chosen.compute(place.rival, place.rival + 1, &rival_cost, &rival_velocity);
    EXPECT_NEAR(expected.score, expected.sequence_difference / rival_cost, 1e-5F) << where;
    EXPECT_NEAR(found.score, expected.score, 1e-5F) << where;
  }
}

}  // namespace
}  // namespace mrs_vpr
