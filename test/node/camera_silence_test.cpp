#include <gtest/gtest.h>

#include <cmath>

#include "mrs_vpr/node/camera_silence.hpp"

namespace mrs_vpr {
namespace node {
namespace {

using Change = CameraSilence::Change;

TEST(CameraSilence, ATopicWithoutImagesIsReportedOnceAfterTheFirstWait) {
  CameraSilence silence;
  silence.listenFrom(100.0);
  EXPECT_EQ(silence.check(101.0), Change::kNone);
  EXPECT_EQ(silence.check(100.0 + CameraSilence::kFirstWait - 0.01), Change::kNone);
  EXPECT_EQ(silence.check(100.0 + CameraSilence::kFirstWait), Change::kSilent);
  EXPECT_FALSE(silence.anyImage());
  EXPECT_DOUBLE_EQ(silence.silentFor(112.0), 12.0);
  // Once: a node kept only for ~query about explicit images logs one warning, not one a period.
  for (double now = 106.0; now < 1000.0; now += 1.0) ASSERT_EQ(silence.check(now), Change::kNone) << now;
}

TEST(CameraSilence, ImagesAfterASilenceAreReportedOnceAndTheNextSilenceAfterTwiceTheWait) {
  CameraSilence silence;
  silence.listenFrom(0.0);
  ASSERT_EQ(silence.check(6.0), Change::kSilent);
  for (double now = 7.0; now < 20.0; now += 1.0 / 30) silence.imageArrived(now);  // a camera at 30 Hz
  EXPECT_TRUE(silence.anyImage());
  EXPECT_EQ(silence.check(20.0), Change::kImagesBack);
  EXPECT_DOUBLE_EQ(silence.silenceAfter(), 2 * CameraSilence::kFirstWait);
  EXPECT_EQ(silence.check(21.0), Change::kNone);
  EXPECT_EQ(silence.check(29.9), Change::kNone);
  EXPECT_EQ(silence.check(30.1), Change::kSilent);  // the camera stopped 10 s ago
  EXPECT_NEAR(silence.silentFor(30.1), 10.1, 0.05);
  EXPECT_EQ(silence.check(400.0), Change::kNone);
  // One image after the long silence, then nothing: the wait does not grow with the silence itself.
  silence.imageArrived(401.0);
  EXPECT_EQ(silence.check(401.5), Change::kImagesBack);
  EXPECT_EQ(silence.check(401.0 + 4 * CameraSilence::kFirstWait), Change::kSilent);
}

TEST(CameraSilence, AMovingCameraIsNeverSilent) {
  CameraSilence silence;
  silence.listenFrom(0.0);
  for (double now = 0.5; now < 300.0; now += 0.1) {
    silence.imageArrived(now);
    ASSERT_EQ(silence.check(now + 0.05), Change::kNone) << now;
  }
}

TEST(CameraSilence, ACameraThatPausesByDesignIsReportedAFewTimesNotAtEveryPause) {
  // 1 s of images, then 8 s without, again and again (a camera gated by motion): the first pause is
  // reported; the wait doubles to 10 s, which the pauses never reach.
  CameraSilence silence;
  silence.listenFrom(0.0);
  int reports = 0;
  for (double now = 0.0; now < 900.0; now += 0.25) {
    if (std::fmod(now, 9.0) < 1.0) silence.imageArrived(now);
    reports += silence.check(now) == Change::kSilent ? 1 : 0;
  }
  EXPECT_EQ(reports, 1);
  // However many pauses were reported, a camera that really stops is reported within kLongestWait.
  CameraSilence flapping;
  flapping.listenFrom(0.0);
  double now = 0.0;
  for (int pause = 0; pause < 20; ++pause) {
    now += flapping.silenceAfter() + 1.0;
    ASSERT_EQ(flapping.check(now), Change::kSilent);
    flapping.imageArrived(now);
    ASSERT_EQ(flapping.check(now), Change::kImagesBack);
  }
  EXPECT_DOUBLE_EQ(flapping.silenceAfter(), CameraSilence::kLongestWait);
}

}  // namespace
}  // namespace node
}  // namespace mrs_vpr
