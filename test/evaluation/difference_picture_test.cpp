#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "mrs_vpr/contrast_enhancement.hpp"
#include "mrs_vpr/difference_matrix.hpp"
#include "mrs_vpr/evaluation/difference_picture.hpp"
#include "support/route_fixture.hpp"

namespace mrs_vpr {
namespace {

constexpr int kWindow = 10;

const testing_support::DescribedRoute& route() {
  static const testing_support::DescribedRoute described = [] {
    SyntheticRouteParams params;
    params.reference_frames = 150;
    params.query_frames = 100;
    params.start_place = 20.0;
    return testing_support::describeRoute(params);
  }();
  return described;
}

TEST(DifferenceOverview, IsTheEnhancedMatrixWhenItFits) {
  const auto& r = route();
  const DifferenceOverview overview = differenceOverview(r.query.view(), r.reference.view(), kWindow, 400, 400);
  EXPECT_EQ(overview.query_stride, 1);
  EXPECT_EQ(overview.reference_stride, 1);
  const cv::Mat expected = enhanceContrast(computeDifferenceMatrix(r.query.view(), r.reference.view()), kWindow);
  ASSERT_EQ(overview.values.size(), expected.size());
  EXPECT_LT(cv::norm(overview.values, expected, cv::NORM_INF), 1e-5);
}

TEST(DifferenceOverview, SamplesQueriesAndKeepsTheLowestOfEachReferenceCell) {
  const auto& r = route();
  const DifferenceOverview overview = differenceOverview(r.query.view(), r.reference.view(), kWindow, 30, 40);
  EXPECT_EQ(overview.query_stride, 4);      // ceil(100 / 30)
  EXPECT_EQ(overview.reference_stride, 4);  // ceil(150 / 40)
  EXPECT_EQ(overview.values.rows, 25);
  EXPECT_EQ(overview.values.cols, 38);  // The last column holds the two remaining frames.
  const cv::Mat full = enhanceContrast(computeDifferenceMatrix(r.query.view(), r.reference.view()), kWindow);
  const auto lowest = [](const cv::Mat& cells) {
    double value = 0.0;
    cv::minMaxLoc(cells, &value);
    return value;
  };
  EXPECT_NEAR(overview.values.at<float>(3, 5), lowest(full.row(12).colRange(20, 24)), 1e-5);
  EXPECT_NEAR(overview.values.at<float>(24, 37), lowest(full.row(96).colRange(148, 150)), 1e-5);
  EXPECT_THROW(differenceOverview(r.query.view(), r.reference.view(), kWindow, 0, 40), std::invalid_argument);
}

TEST(DifferenceBand, FollowsTheTruthWithTheWholeMatrixValues) {
  const auto& r = route();
  const cv::Mat full = enhanceContrast(computeDifferenceMatrix(r.query.view(), r.reference.view()), kWindow);
  std::vector<int> frames;
  std::vector<int> centres;
  for (int q = 0; q < r.query.size(); ++q) {
    frames.push_back(q);
    centres.push_back(r.query_to_reference[static_cast<std::size_t>(q)]);
  }
  const int half = 30;
  const DifferenceBand band = differenceBand(r.query.view(), r.reference.view(), frames, centres, half, kWindow);
  ASSERT_EQ(band.values.rows, 100);
  ASSERT_EQ(band.values.cols, 2 * half + 1);
  int lowest_at_truth = 0;
  for (int q = 0; q < band.values.rows; ++q) {
    cv::Point lowest;
    for (int c = 0; c < band.values.cols; ++c) {
      const int frame = centres[static_cast<std::size_t>(q)] - half + c;
      const float value = band.values.at<float>(q, c);
      if (frame < 0 || frame >= r.reference.size()) {
        EXPECT_TRUE(std::isnan(value)) << q << " " << c;  // Outside the reference.
      } else {
        // Sliding sums over another span of frames round differently in float.
        EXPECT_NEAR(value, full.at<float>(q, frame), 1e-4) << q << " " << c;
      }
    }
    cv::Mat finite = band.values.row(q).clone();
    cv::patchNaNs(finite, 1e9);
    cv::minMaxLoc(finite, nullptr, nullptr, &lowest);
    if (std::abs(lowest.x - half) <= 2) ++lowest_at_truth;
  }
  // Single frames are ambiguous now and then; the place itself is almost always the lowest.
  EXPECT_GE(lowest_at_truth, 80);
  EXPECT_THROW(differenceBand(r.query.view(), r.reference.view(), {100}, {0}, half, kWindow), std::invalid_argument);
  EXPECT_THROW(differenceBand(r.query.view(), r.reference.view(), {1, 2}, {0}, half, kWindow), std::invalid_argument);
}

}  // namespace
}  // namespace mrs_vpr
