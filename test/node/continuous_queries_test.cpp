#include "mrs_vpr/node/continuous_queries.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

namespace mrs_vpr {
namespace node {
namespace {

using Ends = std::vector<int>;

TEST(ContinuousQueryEnds, EveryKeyframeSinceTheLastQuestionEndsOneOldestFirst) {
  EXPECT_EQ(continuousQueryEnds(100, 104, 50, 10), (Ends{101, 102, 103, 104}));
  EXPECT_EQ(continuousQueryEnds(100, 101, 50, 10), (Ends{101}));
}

TEST(ContinuousQueryEnds, BeyondTheBudgetTheyAreThinnedEvenlyWithTheNewest) {
  EXPECT_EQ(continuousQueryEnds(100, 110, 50, 3), (Ends{104, 107, 110}));
  EXPECT_EQ(continuousQueryEnds(100, 110, 50, 1), (Ends{110}));
  EXPECT_EQ(continuousQueryEnds(100, 110, 50, 0), (Ends{110}));  // at least the newest
}

TEST(ContinuousQueryEnds, TheBudgetIsAFifthOfThePeriodByTheLastQuestionsTime) {
  EXPECT_EQ(affordableQueries(1.0, 0.0), 1);     // none timed yet
  EXPECT_EQ(affordableQueries(1.0, 20.0), 10);   // 200 ms of a second
  EXPECT_EQ(affordableQueries(2.0, 20.0), 20);
  EXPECT_EQ(affordableQueries(1.0, 300.0), 0);   // continuousQueryEnds still asks about the newest
  // A day's period and a question of a microsecond: more than an int holds, bounded.
  EXPECT_EQ(affordableQueries(86400.0, 0.001), std::numeric_limits<int>::max());
}

TEST(ContinuousQueryEnds, TheFirstQuestionAndOneAfterTheMapShrankAskAboutTheNewestOnly) {
  EXPECT_EQ(continuousQueryEnds(0, 100000, 50, 1000), (Ends{100000}));  // a large map just loaded
  EXPECT_EQ(continuousQueryEnds(500, 80, 50, 1000), (Ends{80}));        // reset, then 80 new frames
}

TEST(ContinuousQueryEnds, NothingBeforeTheMapHoldsEnoughOrWhenNothingCame) {
  EXPECT_TRUE(continuousQueryEnds(0, 49, 50, 10).empty());
  EXPECT_TRUE(continuousQueryEnds(100, 100, 50, 10).empty());
  // The frames that came before the map could be searched are not asked about afterwards.
  EXPECT_EQ(continuousQueryEnds(40, 52, 50, 10), (Ends{50, 51, 52}));
}

}  // namespace
}  // namespace node
}  // namespace mrs_vpr
