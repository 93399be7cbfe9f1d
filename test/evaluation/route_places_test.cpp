#include "mrs_vpr/evaluation/route_places.hpp"

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

namespace mrs_vpr {
namespace {

/// A route of `views` distinct random views; each listed frame of `stands` is followed by `repeats`
/// copies of its view with sensor noise of a grey level, as a camera standing still records them.
std::vector<cv::Mat> route(int views, const std::vector<int>& stands, int repeats, std::uint64_t seed) {
  cv::RNG rng(seed);
  std::vector<cv::Mat> images;
  for (int view = 0; view < views; ++view) {
    cv::Mat image(32, 64, CV_8UC1);
    rng.fill(image, cv::RNG::UNIFORM, 0, 256);
    images.push_back(image);
    if (std::find(stands.begin(), stands.end(), view) == stands.end()) continue;
    for (int copy = 0; copy < repeats; ++copy) {
      cv::Mat noise(image.size(), CV_16SC1);
      rng.fill(noise, cv::RNG::NORMAL, 0, 1);
      cv::Mat noisy;
      cv::add(image, noise, noisy, cv::noArray(), CV_8U);
      images.push_back(noisy);
    }
  }
  return images;
}

TEST(RoutePlaces, FramesWhereTheCameraStoodAreOnePlace) {
  const std::vector<cv::Mat> images = route(10, {2, 6}, 4, 1);
  ASSERT_EQ(images.size(), 18U);
  const std::vector<int> places = routePlaces({&images});
  const std::vector<int> expected = {0, 1, 2, 2, 2, 2, 2, 3, 4, 5, 6, 6, 6, 6, 6, 7, 8, 9};
  EXPECT_EQ(places, expected);
}

TEST(RoutePlaces, AStepIsStandingOnlyWhenEveryTraversalStood) {
  // The same route twice, but the second camera moved where the first stood after view 6.
  const std::vector<cv::Mat> first = route(10, {2, 6}, 4, 1);
  std::vector<cv::Mat> second = route(10, {2, 6}, 4, 2);
  cv::RNG rng(3);
  for (int i = 11; i <= 14; ++i) rng.fill(second[static_cast<std::size_t>(i)], cv::RNG::UNIFORM, 0, 256);
  const std::vector<int> places = routePlaces({&first, &second});
  const std::vector<int> expected = {0, 1, 2, 2, 2, 2, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13};
  EXPECT_EQ(places, expected);
}

TEST(RoutePlaces, AMovingRouteHasAPlaceForEachFrame) {
  const std::vector<cv::Mat> images = route(12, {}, 0, 4);
  const std::vector<int> places = routePlaces({&images});
  for (int i = 0; i < 12; ++i) EXPECT_EQ(places[static_cast<std::size_t>(i)], i);
}

TEST(RoutePlaces, PlacesOfRouteFrames) {
  const std::vector<int> places = {0, 1, 1, 1, 2};
  EXPECT_EQ(placesOf({4, 0, 2}, places), (std::vector<int>{2, 0, 1}));
  EXPECT_THROW(placesOf({5}, places), std::out_of_range);
  EXPECT_THROW(placesOf({-1}, places), std::out_of_range);
}

TEST(RoutePlaces, RejectsBadInput) {
  const std::vector<cv::Mat> images = route(4, {}, 0, 5);
  const std::vector<cv::Mat> shorter(images.begin(), images.end() - 1);
  EXPECT_THROW(routePlaces({}), std::invalid_argument);
  EXPECT_THROW(routePlaces({&images, &shorter}), std::invalid_argument);
  EXPECT_THROW(routePlaces({&images}, 1.0), std::invalid_argument);
  EXPECT_THROW(routePlaces({&images}, -0.1), std::invalid_argument);
  std::vector<cv::Mat> resized = images;
  resized[2] = cv::Mat(16, 32, CV_8UC1, cv::Scalar(0));
  EXPECT_THROW(routePlaces({&resized}), std::invalid_argument);
  std::vector<cv::Mat> floats = images;
  floats[1] = cv::Mat(32, 64, CV_32FC1, cv::Scalar(0));
  EXPECT_THROW(routePlaces({&floats}), std::invalid_argument);
}

TEST(RoutePlaces, AStandingShareOfZeroMakesEveryFrameAPlaceEvenIdenticalOnes) {
  // Exact copies of a frame (a driver that repeats its last image): at share 0 nothing is standing.
  std::vector<cv::Mat> images = route(6, {}, 0, 5);
  images.insert(images.begin() + 3, images[2].clone());
  images.insert(images.begin() + 3, images[2].clone());
  const std::vector<int> places = routePlaces({&images}, 0.0);
  ASSERT_EQ(places.size(), 8U);
  for (int i = 0; i < 8; ++i) EXPECT_EQ(places[static_cast<std::size_t>(i)], i) << i;
  // At the default share the copies are one place.
  EXPECT_EQ(routePlaces({&images}), (std::vector<int>{0, 1, 2, 2, 2, 3, 4, 5}));
}

}  // namespace
}  // namespace mrs_vpr
