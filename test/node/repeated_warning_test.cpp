#include <gtest/gtest.h>

#include "mrs_vpr/node/repeated_warning.hpp"

namespace mrs_vpr {
namespace node {
namespace {

TEST(RepeatedWarning, LetsEachNewMessageThroughAndARepeatOncePerPeriod) {
  RepeatedWarning warning(5.0);
  EXPECT_TRUE(warning.allows("a", 0.0));
  EXPECT_FALSE(warning.allows("a", 1.0));  // The same mistake again, within the period.
  EXPECT_TRUE(warning.allows("b", 1.1));   // Another: at once.
  EXPECT_TRUE(warning.allows("a", 1.2));   // And the first again, after another.
  EXPECT_FALSE(warning.allows("a", 6.1));
  EXPECT_TRUE(warning.allows("a", 6.2));   // A period after it was last let through.
}

}  // namespace
}  // namespace node
}  // namespace mrs_vpr
