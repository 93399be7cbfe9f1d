// The camera's newest keyframes while the map stays as it is: held in bounded memory, counted from
// the first, copied out for a question.

#include "mrs_vpr/trail.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

namespace mrs_vpr {
namespace {

cv::Mat descriptorOf(int i) { return cv::Mat(1, 8, CV_8UC1, cv::Scalar(i % 256)); }

TEST(Trail, HoldsTheNewestKeyframesAndCountsEveryOne) {
  Trail trail(8, 4);
  for (int i = 0; i < 11; ++i) trail.append(descriptorOf(i), Stamp::fromNanoseconds(100 + i));
  EXPECT_EQ(trail.size(), 11);
  EXPECT_GE(trail.oldest(), 11 - 8);  // at most twice what it keeps
  EXPECT_LE(trail.oldest(), 11 - 4);
  const DescriptorSequence newest = trail.copy(7, 11);
  ASSERT_EQ(newest.size(), 4);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(newest.descriptor(i)[0], 7 + i);
    EXPECT_EQ(newest.stamp(i), Stamp::fromNanoseconds(107 + i));
  }
  try {
    trail.copy(0, 4);
    FAIL() << "no error";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("keyframes 0 to 4 of the trail are not held"), std::string::npos)
        << error.what();
  }
  EXPECT_THROW(trail.copy(7, 12), std::invalid_argument);
  EXPECT_THROW(trail.append(cv::Mat(1, 9, CV_8UC1), Stamp()), std::invalid_argument);
}

}  // namespace
}  // namespace mrs_vpr
