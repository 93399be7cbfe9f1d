#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/place_recognizer.hpp"
#include "mrs_vpr/stamp.hpp"
#include "mrs_vpr/synthetic_route.hpp"

namespace mrs_vpr {
namespace {

/// The latest ROS time, {4294967295, 999999999}: 4294967296.0 as a double, which ROS refuses.
const Stamp kLatest = Stamp::fromSecondsAndNanoseconds(4294967295U, 999999999U);

std::string errorOf(void (*call)()) {
  try {
    call();
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "(no error)";
}

TEST(Stamp, HoldsEveryRosTimeExactly) {
  EXPECT_EQ(kLatest.nanoseconds(), Stamp::kMaxNanoseconds);
  EXPECT_EQ(kLatest.wholeSeconds(), 4294967295U);
  EXPECT_EQ(kLatest.nanosecondsOfSecond(), 999999999U);
  EXPECT_EQ(kLatest.toString(), "4294967295.999999999");
  const Stamp early = Stamp::fromSecondsAndNanoseconds(1700000000U, 123456789U);
  EXPECT_EQ(early.nanoseconds(), 1700000000123456789LL);
  EXPECT_EQ(early.toString(), "1700000000.123456789");
  // Neighbours a nanosecond apart stay apart, where seconds in a double would merge them.
  EXPECT_LT(Stamp::fromNanoseconds(early.nanoseconds() - 1), early);
  EXPECT_EQ(Stamp().nanoseconds(), 0);
  EXPECT_TRUE(Stamp().isZero());
  // An unnormalised time, as a message may carry it, is summed.
  EXPECT_EQ(Stamp::fromSecondsAndNanoseconds(10U, 2500000000U), Stamp::fromSecondsAndNanoseconds(12U, 500000000U));
}

TEST(Stamp, RefusesWhatNoRosTimeCanHoldNamingTheRange) {
  for (const auto call : {+[] { Stamp::fromNanoseconds(-1); },
                          +[] { Stamp::fromNanoseconds(Stamp::kMaxNanoseconds + 1); },
                          +[] { Stamp::fromNanoseconds(std::numeric_limits<std::int64_t>::min()); },
                          +[] { Stamp::fromSecondsAndNanoseconds(4294967295U, 1000000000U); },
                          +[] { Stamp::fromSeconds(-0.5); },
                          +[] { Stamp::fromSeconds(4294967296.0); },
                          +[] { Stamp::fromSeconds(1e300); },
                          +[] { Stamp::fromSeconds(std::nan("")); },
                          +[] { Stamp::fromSeconds(std::numeric_limits<double>::infinity()); }}) {
    const std::string message = errorOf(call);
    EXPECT_NE(message.find("outside 0 .. 4294967295.999999999 s"), std::string::npos) << message;
  }
  EXPECT_NE(errorOf(+[] { Stamp::fromNanoseconds(-1500000000); }).find("stamp -1.500000000 s"), std::string::npos);
}

TEST(Stamp, SecondsRoundToTheNearestNanosecondAsRosDoes) {
  // ros::Time::fromSec: whole seconds by floor, the fraction rounded to nanoseconds.
  EXPECT_EQ(Stamp::fromSeconds(0.0), Stamp());
  EXPECT_EQ(Stamp::fromSeconds(1.5).nanoseconds(), 1500000000);
  EXPECT_EQ(Stamp::fromSeconds(1000.1).nanoseconds(), 1000100000000);
  EXPECT_EQ(Stamp::fromSeconds(4294967295.5).nanoseconds(), 4294967295500000000);
  EXPECT_DOUBLE_EQ(Stamp::fromSeconds(1000.1).seconds(), 1000.1);
  EXPECT_DOUBLE_EQ(kLatest.seconds(), 4294967296.0);  // The nearest double: why stamps are not doubles.
}

TEST(Stamp, TheMapAndItsAnswersCarryTheLatestStampExactly) {
  DescriptorSequence sequence(4);
  sequence.append(cv::Mat(1, 4, CV_8UC1, cv::Scalar(1)), kLatest);
  EXPECT_EQ(sequence.stamp(0), kLatest);

  SyntheticRouteParams route_params;
  route_params.reference_frames = 60;
  route_params.query_frames = 20;
  const SyntheticRoute route = generateSyntheticRoute(route_params);
  RecognizerParams limits;
  limits.recent_exclusion = 5;
  limits.min_appearance_change = 0.0;  // Frame i is map frame i.
  PlaceRecognizer recognizer(Parameters{}, limits);
  for (std::size_t i = 0; i < route.reference.size(); ++i) {
    recognizer.addFrame(route.reference[i], Stamp::fromNanoseconds(Stamp::kMaxNanoseconds - 59 + static_cast<int>(i)));
  }
  EXPECT_EQ(recognizer.state().last_stamp, kLatest);
  EXPECT_EQ(recognizer.state().first_stamp.nanoseconds(), Stamp::kMaxNanoseconds - 59);
  const PlaceAnswer recent = recognizer.matchRecent(10, "seqslam");
  EXPECT_EQ(recent.newest_stamp, kLatest);
  ASSERT_GE(recent.match.reference_index, 0);
  EXPECT_EQ(recent.reference_stamp.nanoseconds(), Stamp::kMaxNanoseconds - 59 + recent.match.reference_index);
}

TEST(Stamp, AFractionJustBelowAWholeNanosecondRoundsUpNotDown) {
  // 12.345678901 s is the double 12.3456789009999994...: its nanoseconds are 345678901, not 345678900.
  EXPECT_EQ(Stamp::fromSeconds(12.345678901).nanoseconds(), 12345678901LL);
  // A stamp of today in seconds: the double 1700000000.2000000476... is nearest to ...200000048 ns.
  EXPECT_EQ(Stamp::fromSeconds(1700000000.2).nanoseconds(), 1700000000200000048LL);
  // So a stamp of whole nanoseconds survives the trip through seconds where a double holds it exactly enough.
  const Stamp stamp = Stamp::fromSecondsAndNanoseconds(12U, 345678901U);
  EXPECT_EQ(Stamp::fromSeconds(stamp.seconds()), stamp);
}

}  // namespace
}  // namespace mrs_vpr
