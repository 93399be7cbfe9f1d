#include <gtest/gtest.h>

#include "mrs_vpr/node/camera_silence.hpp"

namespace mrs_vpr {
namespace node {
namespace {

using Change = CameraSilence::Change;

TEST(CameraSilence, ATopicWithoutImagesIsReportedOnceAfterTheWait) {
  CameraSilence silence;
  silence.listenFrom(100.0);
  EXPECT_EQ(silence.check(101.0), Change::kNone);
  EXPECT_EQ(silence.check(100.0 + CameraSilence::kWarnAfter - 0.01), Change::kNone);
  EXPECT_EQ(silence.check(100.0 + CameraSilence::kWarnAfter), Change::kSilent);
  EXPECT_FALSE(silence.anyImage());
  EXPECT_DOUBLE_EQ(silence.silentFor(112.0), 12.0);
  // Once: a node kept only for ~query about explicit images logs one warning, not one a period.
  for (double now = 106.0; now < 1000.0; now += 1.0) ASSERT_EQ(silence.check(now), Change::kNone) << now;
}

TEST(CameraSilence, ImagesAfterASilenceAreReportedOnceAndANewSilenceAgain) {
  CameraSilence silence;
  silence.listenFrom(0.0);
  ASSERT_EQ(silence.check(6.0), Change::kSilent);
  for (double now = 7.0; now < 20.0; now += 1.0 / 30) silence.imageArrived(now);  // a camera at 30 Hz
  EXPECT_TRUE(silence.anyImage());
  EXPECT_EQ(silence.check(20.0), Change::kImagesBack);
  EXPECT_EQ(silence.check(21.0), Change::kNone);
  EXPECT_EQ(silence.check(24.9), Change::kNone);
  EXPECT_EQ(silence.check(25.1), Change::kSilent);  // the camera stopped 5 s ago
  EXPECT_NEAR(silence.silentFor(25.1), 5.1, 0.05);
  EXPECT_EQ(silence.check(40.0), Change::kNone);
}

TEST(CameraSilence, AMovingCameraIsNeverSilent) {
  CameraSilence silence;
  silence.listenFrom(0.0);
  for (double now = 0.5; now < 300.0; now += 0.1) {
    silence.imageArrived(now);
    ASSERT_EQ(silence.check(now + 0.05), Change::kNone) << now;
  }
}

TEST(CameraSilence, ASlowCameraIsSilentAfterThreeOfItsGaps) {
  // One image every 10 s (a time-lapse camera): silent only after 30 s, so no warning between images.
  CameraSilence silence;
  silence.listenFrom(0.0);
  silence.imageArrived(1.0);
  silence.imageArrived(11.0);
  EXPECT_DOUBLE_EQ(silence.silenceAfter(), 3 * 10.0);
  for (double now = 11.5; now < 41.0; now += 0.5) {
    if (static_cast<int>(now * 2) % 20 == 2) silence.imageArrived(now);  // at 21, 31
    ASSERT_EQ(silence.check(now), Change::kNone) << now;
  }
  EXPECT_EQ(silence.check(31.0 + 30.0), Change::kSilent);
  // A fast camera keeps the shortest wait.
  silence.imageArrived(70.0);
  silence.imageArrived(70.1);
  EXPECT_DOUBLE_EQ(silence.silenceAfter(), CameraSilence::kWarnAfter);
}

}  // namespace
}  // namespace node
}  // namespace mrs_vpr
