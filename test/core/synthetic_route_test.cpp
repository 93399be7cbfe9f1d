#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include <opencv2/core.hpp>

#include "mrs_vpr/synthetic_route.hpp"

namespace mrs_vpr {
namespace {

SyntheticRouteParams smallRoute() {
  SyntheticRouteParams params;
  params.reference_frames = 120;
  params.query_frames = 80;
  params.image_width = 64;
  params.image_height = 32;
  return params;
}

bool identical(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0.0;
}

TEST(SyntheticRoute, SizesAndTypesFollowTheParameters) {
  const SyntheticRouteParams params = smallRoute();
  const SyntheticRoute route = generateSyntheticRoute(params);
  ASSERT_EQ(route.reference.size(), 120U);
  ASSERT_EQ(route.query.size(), 80U);
  ASSERT_EQ(route.query_to_reference.size(), 80U);
  for (const std::vector<cv::Mat>* frames : {&route.reference, &route.query}) {
    for (const cv::Mat& frame : *frames) {
      EXPECT_EQ(frame.type(), CV_8UC3);
      EXPECT_EQ(frame.cols, 64);
      EXPECT_EQ(frame.rows, 32);
    }
  }
}

TEST(SyntheticRoute, SameSeedGivesIdenticalImagesAnotherSeedDoesNot) {
  const SyntheticRouteParams params = smallRoute();
  const SyntheticRoute a = generateSyntheticRoute(params);
  const SyntheticRoute b = generateSyntheticRoute(params);
  for (std::size_t i = 0; i < a.reference.size(); ++i) ASSERT_TRUE(identical(a.reference[i], b.reference[i])) << i;
  for (std::size_t i = 0; i < a.query.size(); ++i) ASSERT_TRUE(identical(a.query[i], b.query[i])) << i;
  EXPECT_EQ(a.query_to_reference, b.query_to_reference);

  SyntheticRouteParams other = params;
  other.seed = params.seed + 1;
  const SyntheticRoute c = generateSyntheticRoute(other);
  EXPECT_FALSE(identical(a.reference[0], c.reference[0]));
  EXPECT_FALSE(identical(a.query[10], c.query[10]));
}

TEST(SyntheticRoute, AlignmentIncreasesWithStepsWithinTheSpeedRange) {
  SyntheticRouteParams params = smallRoute();
  params.start_place = 5.0;
  const SyntheticRoute route = generateSyntheticRoute(params);
  const std::vector<int>& truth = route.query_to_reference;
  EXPECT_EQ(truth.front(), 5);
  for (std::size_t i = 1; i < truth.size(); ++i) {
    const int step = truth[i] - truth[i - 1];
    // Speeds in [0.8, 1.2] places per frame, rounded to whole frames.
    EXPECT_GE(step, 0) << "query frame " << i;
    EXPECT_LE(step, 2) << "query frame " << i;
  }
  EXPECT_GT(truth.back(), truth.front());
  const double mean_speed = static_cast<double>(truth.back() - truth.front()) / (truth.size() - 1);
  EXPECT_GE(mean_speed, 0.8 - 0.02);
  EXPECT_LE(mean_speed, 1.2 + 0.02);
}

TEST(SyntheticRoute, ConstantSpeedOneGivesTheIdentityAlignment) {
  SyntheticRouteParams params = smallRoute();
  params.speed_min = 1.0;
  params.speed_max = 1.0;
  params.start_place = 10.0;
  const SyntheticRoute route = generateSyntheticRoute(params);
  for (std::size_t i = 0; i < route.query_to_reference.size(); ++i) {
    EXPECT_EQ(route.query_to_reference[i], 10 + static_cast<int>(i));
  }
}

TEST(SyntheticRoute, QueryFramesLookLikeTheirReferencePlaceMoreThanAFarOne) {
  const SyntheticRoute route = generateSyntheticRoute(smallRoute());
  cv::Mat query;
  cv::Mat near;
  cv::Mat far;
  route.query[40].convertTo(query, CV_32F);
  route.reference[static_cast<std::size_t>(route.query_to_reference[40])].convertTo(near, CV_32F);
  route.reference[static_cast<std::size_t>((route.query_to_reference[40] + 60) % 120)].convertTo(far, CV_32F);
  // Correlation of mean-free images: illumination changes neither sign nor order.
  auto correlation = [](cv::Mat a, cv::Mat b) {
    a -= cv::mean(a);
    b -= cv::mean(b);
    return a.dot(b) / std::sqrt(a.dot(a) * b.dot(b));
  };
  EXPECT_GT(correlation(query, near), correlation(query, far));
}

TEST(SyntheticRoute, ThrowsWhenTheSecondTraversalLeavesTheRoute) {
  SyntheticRouteParams params = smallRoute();
  params.reference_frames = 50;
  params.query_frames = 100;
  try {
    generateSyntheticRoute(params);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("leaves the route"), std::string::npos) << error.what();
  }
  params = smallRoute();
  params.start_place = -1.0;
  EXPECT_THROW(generateSyntheticRoute(params), std::invalid_argument);
}

TEST(SyntheticRoute, InvalidSizesAndSpeedsThrow) {
  SyntheticRouteParams params = smallRoute();
  params.reference_frames = 1;
  EXPECT_THROW(generateSyntheticRoute(params), std::invalid_argument);
  params = smallRoute();
  params.image_width = 4;
  EXPECT_THROW(generateSyntheticRoute(params), std::invalid_argument);
  params = smallRoute();
  params.image_width = 2147483647;  // The world's width overflowed an int and OpenCV asserted.
  EXPECT_THROW(generateSyntheticRoute(params), std::invalid_argument);
  params = smallRoute();
  params.speed_min = 1.3;
  EXPECT_THROW(generateSyntheticRoute(params), std::invalid_argument);
  params = smallRoute();
  params.speed_min = 0.0;
  EXPECT_THROW(generateSyntheticRoute(params), std::invalid_argument);
}

}  // namespace
}  // namespace mrs_vpr
