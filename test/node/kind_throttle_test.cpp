#include <gtest/gtest.h>

#include <string>

#include "mrs_vpr/node/kind_throttle.hpp"

namespace mrs_vpr {
namespace node {
namespace {

TEST(KindThrottle, LetsEachKindThroughOncePerPeriodWhateverComesBetween) {
  KindThrottle throttle(5.0);
  EXPECT_TRUE(throttle.allows("a", 0.0));
  EXPECT_FALSE(throttle.allows("a", 1.0));  // The same kind again, within the period.
  EXPECT_TRUE(throttle.allows("b", 1.1));   // Another: at once.
  EXPECT_FALSE(throttle.allows("a", 1.2));  // The first again, though another came between.
  EXPECT_FALSE(throttle.allows("b", 2.0));
  EXPECT_TRUE(throttle.allows("a", 5.0));   // A period after it was last let through.
  EXPECT_FALSE(throttle.allows("a", 9.9));
  EXPECT_TRUE(throttle.allows("b", 6.1));
}

TEST(KindThrottle, KindsBeyondTheRememberedShareOnePeriodAndMemoryStaysBounded) {
  KindThrottle throttle(5.0);
  for (std::size_t i = 0; i < KindThrottle::kRemembered; ++i) {
    EXPECT_TRUE(throttle.allows("kind " + std::to_string(i), 0.0));
  }
  // Messages that differ in more than numbers could be ever new kinds: together they are one.
  EXPECT_TRUE(throttle.allows("one more", 0.5));
  EXPECT_FALSE(throttle.allows("and another", 0.6));
  EXPECT_FALSE(throttle.allows("kind 3", 0.7));
  for (int i = 0; i < 1000; ++i) EXPECT_FALSE(throttle.allows("new " + std::to_string(i) + "x", 1.0 + 0.001 * i));
  EXPECT_LE(throttle.remembered(), KindThrottle::kRemembered + 1);
  // The kinds told apart keep their own periods: kind 3's is over while the shared one (from 0.5) is not.
  EXPECT_TRUE(throttle.allows("kind 3", 5.1));
  // A period later the old kinds are forgotten, and new kinds are told apart again.
  EXPECT_TRUE(throttle.allows("a new kind", 6.0));
  EXPECT_EQ(throttle.remembered(), 2U);  // kind 3 (5.1) and the new one
  EXPECT_TRUE(throttle.allows("another new kind", 6.1));
  EXPECT_FALSE(throttle.allows("a new kind", 7.0));
}

TEST(KindThrottle, AProblemsKindLeavesOutTheFramesNumbers) {
  EXPECT_EQ(kindOf("step 299 is less than width 100 x 3 bytes of bgr8"),
            "step # is less than width # x # bytes of bgr#");
  EXPECT_EQ(kindOf("empty image (0 x 480 px)"), "empty image (# x # px)");
  EXPECT_EQ(kindOf(""), "");
  EXPECT_EQ(kindOf("data holds 10 bytes, but step x height needs 4000"),
            kindOf("data holds 77 bytes, but step x height needs 12"));
}

}  // namespace
}  // namespace node
}  // namespace mrs_vpr
