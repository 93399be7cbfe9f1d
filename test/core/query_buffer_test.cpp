#include <thread>

#include <gtest/gtest.h>

#include "mrs_vpr/query_buffer.hpp"
#include "mrs_vpr/seqslam_matcher.hpp"
#include "support/route_fixture.hpp"

namespace mrs_vpr {
namespace {

// A map that grows by a frame between queries keeps the same storage: no fresh pages per query.
TEST(QueryBuffer, AGrowingMapReusesTheStorage) {
  QueryBuffer buffer;
  cv::Mat first = buffer.matrix(50, 10000);
  first.setTo(1.0F);
  const float* storage = first.ptr<float>();
  for (int columns = 10001; columns < 10100; ++columns) {
    const cv::Mat next = buffer.matrix(50, columns);
    EXPECT_EQ(next.ptr<float>(), storage) << columns;
    EXPECT_EQ(next.rows, 50);
    EXPECT_EQ(next.cols, columns);
    EXPECT_EQ(next.type(), CV_32FC1);
  }
  buffer.release();  // Below the limit: kept.
  EXPECT_GE(buffer.capacityBytes(), 50U * 10099U * sizeof(float));
}

TEST(QueryBuffer, ABufferAboveTheLimitIsHandedBack) {
  QueryBuffer buffer;
  const int columns = static_cast<int>(kKeptQueryBufferBytes / sizeof(float) / 100) + 1;
  EXPECT_EQ(buffer.matrix(100, columns).cols, columns);
  buffer.release();
  EXPECT_EQ(buffer.capacityBytes(), 0U);
}

// The brute force's kept matrices give each query its own answer: a longer query after a shorter
// one, and the shorter again, are answered as by a fresh thread.
TEST(QueryBuffer, TheBruteForceGivesTheSameAnswersWithKeptMatrices) {
  const auto& route = testing_support::standardRoute();
  const SeqSlamMatcher matcher(testing_support::routeParameters().sequence);
  const SequenceView map = route.reference.view();
  Match first;
  Match again;
  std::thread([&] { first = matcher.match(map, route.query.view(100, 120)); }).join();
  std::thread([&] {
    matcher.match(map.slice(0, 400), route.query.view(200, 250));
    again = matcher.match(map, route.query.view(100, 120));
  }).join();
  EXPECT_EQ(again.reference_index, first.reference_index);
  EXPECT_EQ(again.sequence_difference, first.sequence_difference);
  EXPECT_EQ(again.confidence, first.confidence);
}

}  // namespace
}  // namespace mrs_vpr
