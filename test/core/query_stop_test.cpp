#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <random>
#include <thread>
#include <vector>

#include <opencv2/core.hpp>

#include "mrs_vpr/contrast_enhancement.hpp"
#include "mrs_vpr/difference_matrix.hpp"
#include "mrs_vpr/place_recognizer.hpp"
#include "mrs_vpr/query_stop.hpp"
#include "mrs_vpr/sequence_matcher.hpp"
#include "mrs_vpr/trajectory_search.hpp"
#include "support/route_fixture.hpp"

namespace mrs_vpr {
namespace {

using testing_support::globalSearchParams;
using testing_support::standardRoute;

/// `frames` descriptors of `size` random bytes.
DescriptorSequence randomFrames(int frames, int size, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> byte(0, 255);
  DescriptorSequence sequence(size);
  cv::Mat descriptor(1, size, CV_8UC1);
  for (int i = 0; i < frames; ++i) {
    for (int b = 0; b < size; ++b) descriptor.at<std::uint8_t>(0, b) = static_cast<std::uint8_t>(byte(random));
    sequence.append(descriptor);
  }
  return sequence;
}

// Each stage of the brute force refuses to go on once a stop is asked for, and a stop never asked
// for changes nothing.
TEST(QueryStop, EachStageOfTheBruteForceStopsWhenAsked) {
  const auto& route = standardRoute();
  const SequenceView map = route.reference.view();
  const SequenceView query = route.query.view(100, 150);
  const SequenceParams params = globalSearchParams().sequence;
  const QueryStop never;
  QueryStop stop;
  stop.request();

  cv::Mat differences(query.count, map.count, CV_32F);
  computeDifferenceMatrix(query, map, differences, &never);
  EXPECT_EQ(cv::norm(differences, computeDifferenceMatrix(query, map), cv::NORM_INF), 0.0);
  cv::Mat stopped_differences(query.count, map.count, CV_32F);
  EXPECT_THROW(computeDifferenceMatrix(query, map, stopped_differences, &stop), QueryStopped);

  cv::Mat enhanced = differences.clone();
  enhanceContrastInPlace(enhanced, params.contrast_window, &never);
  EXPECT_EQ(cv::norm(enhanced, enhanceContrast(differences, params.contrast_window), cv::NORM_INF), 0.0);
  cv::Mat stopped_enhanced = differences.clone();
  EXPECT_THROW(enhanceContrastInPlace(stopped_enhanced, params.contrast_window, &stop), QueryStopped);

  const SequenceRows rows = wholeSequenceRows(query.count, params.alignment);
  const Match match = searchTrajectories(enhanced, rows, params, &never);
  EXPECT_EQ(match.reference_index, searchTrajectories(enhanced, rows, params).reference_index);
  EXPECT_EQ(match.confidence, searchTrajectories(enhanced, rows, params).confidence);
  EXPECT_THROW(searchTrajectories(enhanced, rows, params, &stop), QueryStopped);
}

// A brute-force question that is running when the stop comes ends with QueryStopped: the matcher
// itself checks nothing at its start, so only the stages' checks can end it.
TEST(QueryStop, ARunningBruteForceQuestionEndsWhenAsked) {
  const int size = 756;
  const DescriptorSequence map = randomFrames(20000, size, 1);
  const DescriptorSequence query = randomFrames(500, size, 2);
  const auto matcher = makeMatcher("seqslam", globalSearchParams());
  QueryStop stop;
  matcher->stopWith(&stop);
  std::atomic<bool> started{false};
  bool stopped = false;
  std::thread asking([&] {
    started = true;
    try {
      matcher->match(map.view(), query.view());
    } catch (const QueryStopped&) {
      stopped = true;
    }
  });
  while (!started) std::this_thread::yield();
  // The question compares 10 million pairs of 756 bytes: far longer than this.
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  stop.request();
  asking.join();
  EXPECT_TRUE(stopped);
}

// MRS stops in its coarsest level, most of a long question: the tiled one of a query with coarser
// levels, and the dense one of a query without.
TEST(QueryStop, AnMrsQuestionStopsInItsCoarsestLevel) {
  const auto& route = standardRoute();
  const auto matcher = makeMatcher("mrs", globalSearchParams());
  QueryStop stop;
  matcher->stopWith(&stop);
  for (const int frames : {300, 100}) {
    EXPECT_GE(matcher->match(route.reference.view(), route.query.view(0, frames)).reference_index, 0);
  }
  stop.request();
  for (const int frames : {300, 100}) {
    EXPECT_THROW(matcher->match(route.reference.view(), route.query.view(0, frames)), QueryStopped) << frames;
  }
}

TEST(QueryStop, AStoppedRecognizerRefusesQuestionsAndStillTakesFrames) {
  const auto& images = testing_support::standardRouteImages();
  PlaceRecognizer recognizer(globalSearchParams());
  for (int i = 0; i < 300; ++i) recognizer.addFrame(images.reference[static_cast<std::size_t>(i)]);
  const std::vector<cv::Mat> question(images.query.begin() + 100, images.query.begin() + 130);
  EXPECT_GE(recognizer.match(question, "seqslam").match.reference_index, 0);
  recognizer.stopQueries();
  EXPECT_THROW(recognizer.match(question, "seqslam"), QueryStopped);
  EXPECT_THROW(recognizer.match(question, "mrs"), QueryStopped);
  EXPECT_THROW(recognizer.matchRecent(20), QueryStopped);
  const int frames = recognizer.size();
  EXPECT_EQ(recognizer.addFrame(images.reference[400]), FrameAdmission::kAdmitted);
  EXPECT_EQ(recognizer.size(), frames + 1);
}

}  // namespace
}  // namespace mrs_vpr
