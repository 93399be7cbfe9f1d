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

TEST(KindThrottle, ManyKindsWithinAPeriodKeepItsMemoryBounded) {
  KindThrottle throttle(5.0);
  for (std::size_t i = 0; i <= 3 * KindThrottle::kRemembered; ++i) {
    EXPECT_TRUE(throttle.allows("kind " + std::to_string(i), 0.0));
  }
  EXPECT_TRUE(throttle.allows("the newest", 1.0));
  EXPECT_FALSE(throttle.allows("the newest", 2.0));
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
