#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "mrs_vpr/difference_matrix.hpp"
#include "mrs_vpr/match_explanation.hpp"
#include "mrs_vpr/place_recognizer.hpp"
#include "support/route_fixture.hpp"

namespace mrs_vpr {
namespace {

using testing_support::globalSearchParams;
using testing_support::routeDescriptor;
using testing_support::standardRoute;
using testing_support::within;

/// A recognizer whose map is the standard route's reference traversal (descriptors).
void mapReference(PlaceRecognizer& recognizer) {
  const SequenceView reference = standardRoute().reference.view();
  for (int i = 0; i < reference.count; ++i) {
    recognizer.addDescriptor(
        cv::Mat(1, reference.descriptor_size, CV_8UC1, const_cast<std::uint8_t*>(reference.frame(i))),
        Stamp::fromSecondsAndNanoseconds(static_cast<std::uint32_t>(i), 0));
  }
}

TEST(MatchExplanation, TheTrajectoryEndsAtTheAnswerAndFollowsTheTrueAlignment) {
  const auto& route = standardRoute();
  const Parameters params = globalSearchParams();
  const SequenceView query = route.query.view(100, 250);  // 150 frames
  const SequenceView reference = route.reference.view();
  const int truth = route.query_to_reference[249];
  Match match;
  match.reference_index = truth;
  const MatchExplanation explanation = explainMatch(reference, query, match, params.sequence, params.descriptor);

  ASSERT_EQ(static_cast<int>(explanation.trajectory.size()), 150);
  EXPECT_EQ(explanation.anchor, 149);  // causal: the newest frame
  EXPECT_EQ(explanation.trajectory.back(), truth);
  // The route's speed varies within 0.8..1.2: a straight line stays near the truth all along.
  for (int t = 0; t < 150; t += 10) {
    EXPECT_TRUE(within(explanation.trajectory[static_cast<std::size_t>(t)], route.query_to_reference[100 + t], 12))
        << "test frame " << t << ": " << explanation.trajectory[static_cast<std::size_t>(t)];
  }
  EXPECT_GE(explanation.velocity, params.sequence.velocity_min);
  EXPECT_LE(explanation.velocity, params.sequence.velocity_max);

  // The band covers the trajectory with a margin, within kMaxBandSide cells a side.
  EXPECT_EQ(explanation.band.type(), CV_32FC1);
  EXPECT_LE(explanation.band.rows, kMaxBandSide);
  EXPECT_LE(explanation.band.cols, kMaxBandSide);
  EXPECT_LT(explanation.band_first, explanation.trajectory.front() - 5);
  EXPECT_GT(explanation.band_first + explanation.band.cols * explanation.band_step, truth + 5);
  // Its cells are the raw differences of the frames they stand for, on grids through the answer.
  const int step = explanation.band_step;
  const int first_row = explanation.band_first_row;
  EXPECT_EQ(explanation.band.rows, (149 - first_row) / step + 1);
  EXPECT_EQ((149 - first_row) % step, 0);
  EXPECT_EQ((truth - explanation.band_first) % step, 0);
  for (const auto& [row, column] : std::vector<std::pair<int, int>>{{0, 0}, {3, 7}, {explanation.band.rows - 1, 2}}) {
    EXPECT_FLOAT_EQ(explanation.band.at<float>(row, column),
                    descriptorDifference(query.frame(first_row + row * step),
                                         reference.frame(explanation.band_first + column * step),
                                         query.descriptor_size));
  }
  // Along the trajectory the band is darker (more similar) than on average.
  double along = 0.0;
  for (int row = 0; row < explanation.band.rows; ++row) {
    const int frame = explanation.trajectory[static_cast<std::size_t>(first_row + row * step)];
    along += explanation.band.at<float>(row, (frame - explanation.band_first) / step);
  }
  EXPECT_LT(along / explanation.band.rows, 0.8 * cv::mean(explanation.band)[0]);

  // Thumbnails are the descriptors, shaped as images.
  ASSERT_EQ(explanation.query_thumbnail.size(), cv::Size(64, 32));
  ASSERT_EQ(explanation.reference_thumbnail.size(), cv::Size(64, 32));
  EXPECT_EQ(explanation.query_thumbnail.at<std::uint8_t>(1, 2), query.frame(149)[64 + 2]);
  EXPECT_EQ(explanation.reference_thumbnail.at<std::uint8_t>(1, 2), reference.frame(truth)[64 + 2]);
}

TEST(MatchExplanation, NoMatchGivesOnlyTheQueryThumbnail) {
  const auto& route = standardRoute();
  const MatchExplanation explanation =
      explainMatch(route.reference.view(), route.query.view(0, 20), Match{}, SequenceParams{}, routeDescriptor());
  EXPECT_FALSE(explanation.query_thumbnail.empty());
  EXPECT_TRUE(explanation.reference_thumbnail.empty());
  EXPECT_TRUE(explanation.band.empty());
  EXPECT_TRUE(explanation.trajectory.empty());
}

TEST(MatchExplanation, ExplainingAQueryDoesNotChangeItsAnswer) {
  PlaceRecognizer recognizer(globalSearchParams());
  mapReference(recognizer);
  const SequenceView query = standardRoute().query.view(100, 250);  // mrs uses one coarser level
  for (const std::string method : {"mrs", "seqslam"}) {
    SCOPED_TRACE(method);
    const PlaceAnswer plain = recognizer.match(query, method);
    MatchExplanation explanation;
    const PlaceAnswer explained = recognizer.match(query, method, &explanation);
    EXPECT_EQ(explained.match.reference_index, plain.match.reference_index);
    EXPECT_FLOAT_EQ(explained.match.confidence, plain.match.confidence);
    EXPECT_EQ(explained.match.accepted, plain.match.accepted);
    EXPECT_EQ(explanation.trajectory.back(), plain.match.reference_index);
    EXPECT_EQ(explanation.reference_frames, 600);
    // Only MRS has levels to show: here the coarse one (stride 2) and full resolution.
    if (method == "mrs") {
      ASSERT_EQ(explanation.levels.size(), 2U);
      EXPECT_EQ(explanation.levels[0].stride, 2);
      EXPECT_EQ(explanation.levels[1].stride, 1);
      EXPECT_FALSE(explanation.levels[0].candidates.empty());
      EXPECT_TRUE(within(explanation.levels[1].candidates.front(), plain.match.reference_index, 1));
    } else {
      EXPECT_TRUE(explanation.levels.empty());
    }
  }
}

TEST(MatchExplanation, MatchRecentExplainsTheNewestFrames) {
  RecognizerParams limits;
  limits.recent_exclusion = 50;
  PlaceRecognizer recognizer(globalSearchParams(), limits);
  mapReference(recognizer);
  const SequenceView query = standardRoute().query.view();
  for (int i = 100; i < 250; ++i) {
    recognizer.addDescriptor(cv::Mat(1, query.descriptor_size, CV_8UC1, const_cast<std::uint8_t*>(query.frame(i))),
                             Stamp::fromSecondsAndNanoseconds(static_cast<std::uint32_t>(1000 + i), 0));
  }
  MatchExplanation explanation;
  const PlaceAnswer answer = recognizer.matchRecent(150, "seqslam", &explanation);
  EXPECT_EQ(explanation.query_frames, 150);
  EXPECT_EQ(explanation.reference_frames, 750 - 150 - 50);
  EXPECT_EQ(explanation.trajectory.back(), answer.match.reference_index);
  EXPECT_EQ(explanation.query_thumbnail.at<std::uint8_t>(0, 5), query.frame(249)[5]);
}

}  // namespace
}  // namespace mrs_vpr
