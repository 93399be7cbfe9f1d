#include "mrs_vpr/number_text.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace mrs_vpr {
namespace {

TEST(NumberText, WritesNumbersAsAPersonWritesThem) {
  EXPECT_EQ(numberText(0.4), "0.4");  // std::to_string: 0.400000; boost's --help: 0.40000000000000002
  EXPECT_EQ(numberText(3.0), "3");
  EXPECT_EQ(numberText(1000000.0), "1000000");  // not 1e+06
  EXPECT_EQ(numberText(-2.5), "-2.5");
  EXPECT_EQ(numberText(1e-10), "1e-10");
  EXPECT_EQ(numberText(std::numeric_limits<double>::infinity()), "inf");
}

}  // namespace
}  // namespace mrs_vpr
