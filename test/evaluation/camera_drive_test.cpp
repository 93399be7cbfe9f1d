#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "mrs_vpr/evaluation/camera_drive.hpp"
#include "mrs_vpr/synthetic_route.hpp"
#include "support/error_message.hpp"

namespace mrs_vpr {
namespace {

using testing_support::invalidArgumentMessage;

CameraDriveSettings smallDrive(std::uint64_t seed = 3) {
  CameraDriveSettings settings;
  settings.seed = seed;
  settings.stops = 3;
  settings.stop_frames_min = 5;
  settings.stop_frames_max = 12;
  settings.slow_frames = 20;
  settings.fast_frames = 20;
  return settings;
}

/// Route images of one grey level each (frame r is grey 100 + r % 100), `width` x width / 2, bgr8.
std::vector<cv::Mat> flatRoute(int frames, int width = 64) {
  std::vector<cv::Mat> route;
  for (int r = 0; r < frames; ++r) route.emplace_back(width / 2, width, CV_8UC3, cv::Scalar::all(100 + r % 100));
  return route;
}

/// The runs of stopped frames: (first drive frame, length).
std::vector<std::pair<int, int>> stopsOf(const CameraDrive& drive) {
  std::vector<std::pair<int, int>> stops;
  for (int i = 0; i < drive.size(); ++i) {
    const DriveFrame& frame = drive.frames()[static_cast<std::size_t>(i)];
    if (frame.kind != DriveFrameKind::kStopped) continue;
    if (frame.stop_frame == 0) stops.emplace_back(i, 0);
    ++stops.back().second;
  }
  return stops;
}

TEST(CameraDrive, EveryRouteFrameInOrderWithStopsAndOneStretchAtEachSpeed) {
  const CameraDriveSettings settings = smallDrive();
  const int route = 200;
  const CameraDrive drive(route, settings);
  const std::vector<std::pair<int, int>> stops = stopsOf(drive);
  ASSERT_EQ(stops.size(), 3U);
  int stopped = 0;
  for (const auto& [first, length] : stops) {
    EXPECT_GE(length, settings.stop_frames_min);
    EXPECT_LE(length, settings.stop_frames_max);
    stopped += length;
    // The vehicle stops where it is: the frame before the stop shows the same route frame, moving.
    const DriveFrame& before = drive.frames()[static_cast<std::size_t>(first - 1)];
    EXPECT_EQ(before.kind, DriveFrameKind::kMoving);
    EXPECT_EQ(before.route_frame, drive.frames()[static_cast<std::size_t>(first)].route_frame);
  }
  // 200 route frames, 10 of the double-speed stretch left out, 20 shown twice, and the stops.
  EXPECT_EQ(drive.size(), route - 10 + 20 + stopped);

  ASSERT_GE(drive.slowBegin(), 0);
  ASSERT_GE(drive.fastBegin(), 0);
  const bool overlap = drive.slowBegin() < drive.fastBegin() + settings.fast_frames &&
                       drive.fastBegin() < drive.slowBegin() + settings.slow_frames;
  EXPECT_FALSE(overlap);
  std::vector<int> shown(route, 0);
  int previous = 0;
  for (const DriveFrame& frame : drive.frames()) {
    EXPECT_GE(frame.route_frame, previous) << "a drive goes forward only";
    previous = frame.route_frame;
    ++shown[static_cast<std::size_t>(frame.route_frame)];
  }
  for (int r = 0; r < route; ++r) {
    SCOPED_TRACE("route frame " + std::to_string(r));
    const bool slow = r >= drive.slowBegin() && r < drive.slowBegin() + settings.slow_frames;
    const bool fast = r >= drive.fastBegin() && r < drive.fastBegin() + settings.fast_frames;
    if (fast) {
      EXPECT_EQ(shown[static_cast<std::size_t>(r)], (r - drive.fastBegin()) % 2 == 0 ? 1 : 0);
    } else if (slow) {
      EXPECT_EQ(shown[static_cast<std::size_t>(r)], 2);
    } else {
      EXPECT_GE(shown[static_cast<std::size_t>(r)], 1);
    }
  }
  // No stop inside a stretch.
  for (const auto& stop : stops) {
    const int r = drive.frames()[static_cast<std::size_t>(stop.first)].route_frame;
    EXPECT_FALSE(r >= drive.slowBegin() && r < drive.slowBegin() + settings.slow_frames);
    EXPECT_FALSE(r >= drive.fastBegin() && r < drive.fastBegin() + settings.fast_frames);
  }
}

TEST(CameraDrive, TheDefaultsAreEightStopsOf30To90FramesAndStretchesOf100) {
  const CameraDrive drive(1783);
  const std::vector<std::pair<int, int>> stops = stopsOf(drive);
  ASSERT_EQ(stops.size(), 8U);
  for (const auto& stop : stops) {
    EXPECT_GE(stop.second, 30);
    EXPECT_LE(stop.second, 90);
  }
  int slow = 0;
  for (const DriveFrame& frame : drive.frames()) slow += frame.kind == DriveFrameKind::kSlowCopy ? 1 : 0;
  EXPECT_EQ(slow, 100);
}

TEST(CameraDrive, NoStoppedOrSlowFrameIsAnExactCopy) {
  const SyntheticRoute generated = generateSyntheticRoute(SyntheticRouteParams{});
  const CameraDrive drive(static_cast<int>(generated.reference.size()), smallDrive());
  const std::vector<cv::Mat> images = renderDrive(drive, generated.reference);
  ASSERT_EQ(images.size(), static_cast<std::size_t>(drive.size()));
  for (int i = 0; i < drive.size(); ++i) {
    const DriveFrame& frame = drive.frames()[static_cast<std::size_t>(i)];
    const cv::Mat& original = generated.reference[static_cast<std::size_t>(frame.route_frame)];
    const double change = cv::norm(images[static_cast<std::size_t>(i)], original, cv::NORM_INF);
    if (frame.kind == DriveFrameKind::kMoving) {
      EXPECT_EQ(change, 0.0) << "drive frame " << i << " is the route frame itself";
    } else {
      EXPECT_GT(change, 0.0) << "drive frame " << i << " (" << toString(frame.kind) << ") is an exact copy";
    }
    if (i > 0 && frame.kind == DriveFrameKind::kStopped) {
      EXPECT_GT(cv::norm(images[static_cast<std::size_t>(i)], images[static_cast<std::size_t>(i) - 1], cv::NORM_INF),
                0.0)
          << "stopped frame " << i << " repeats the frame before it";
    }
  }
}

TEST(CameraDrive, ACopyIsNeverExactEvenWhenTheNoiseRoundsAway) {
  // Noise far below a grey level, no vibration, no gain: rounding alone would give the route frame back.
  CameraDriveSettings settings = smallDrive();
  settings.noise_std = 0.001;
  settings.vibration = 0.0;
  settings.gain = 0.0;
  const std::vector<cv::Mat> route = flatRoute(100);
  const CameraDrive drive(100, settings);
  int copies = 0;
  for (int i = 0; i < drive.size(); ++i) {
    const DriveFrame& frame = drive.frames()[static_cast<std::size_t>(i)];
    if (frame.kind != DriveFrameKind::kSlowCopy) continue;
    // One pixel of one channel moves by one grey level.
    EXPECT_EQ(cv::norm(drive.render(i, route[static_cast<std::size_t>(frame.route_frame)]),
                       route[static_cast<std::size_t>(frame.route_frame)], cv::NORM_L1),
              1.0)
        << "drive frame " << i;
    ++copies;
  }
  EXPECT_EQ(copies, settings.slow_frames);
}

TEST(CameraDrive, TheSameSeedGivesTheSameDriveAndAnotherSeedAnother) {
  const std::vector<cv::Mat> route = generateSyntheticRoute(SyntheticRouteParams{}).reference;
  const int frames = static_cast<int>(route.size());
  const CameraDrive first(frames, smallDrive(5));
  const CameraDrive again(frames, smallDrive(5));
  ASSERT_EQ(routeFramesOf(first.frames()), routeFramesOf(again.frames()));
  const std::vector<cv::Mat> a = renderDrive(first, route);
  const std::vector<cv::Mat> b = renderDrive(again, route);
  for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(cv::norm(a[i], b[i], cv::NORM_INF), 0.0) << "drive frame " << i;
  // A frame drawn on its own is the frame drawn in sequence.
  const int last = first.size() - 1;
  EXPECT_EQ(cv::norm(first.render(last, route[static_cast<std::size_t>(first.frames().back().route_frame)]), a.back(),
                     cv::NORM_INF),
            0.0);

  const CameraDrive other(frames, smallDrive(6));
  EXPECT_NE(routeFramesOf(other.frames()), routeFramesOf(first.frames()));
}

TEST(CameraDrive, APasserByCrossesTheViewDuringEachStop) {
  const std::vector<cv::Mat> route = flatRoute(120);
  CameraDriveSettings settings = smallDrive();
  settings.stop_frames_min = settings.stop_frames_max = 40;
  const CameraDrive drive(120, settings);
  const std::vector<cv::Mat> images = renderDrive(drive, route);
  for (const auto& [first, length] : stopsOf(drive)) {
    SCOPED_TRACE("stop at drive frame " + std::to_string(first));
    const cv::Mat& background =
        route[static_cast<std::size_t>(drive.frames()[static_cast<std::size_t>(first)].route_frame)];
    std::vector<double> centres;
    for (int i = first; i < first + length; ++i) {
      // The figure: far darker than the view (noise is 0.5 grey levels), measured where it covers
      // half a pixel or more (its edges are anti-aliased).
      cv::Mat grey;
      cv::extractChannel(images[static_cast<std::size_t>(i)], grey, 0);
      const double view = background.at<cv::Vec3b>(0, 0)[0];
      double darkest = 0.0;
      cv::minMaxLoc(grey, &darkest);
      if (darkest > 0.8 * view) continue;  // Not yet in the view, or gone.
      const cv::Mat figure = grey < (view + darkest) / 2.0;
      const cv::Moments moments = cv::moments(figure, true);
      centres.push_back(moments.m10 / moments.m00);
      const cv::Rect box = cv::boundingRect(figure);
      if (box.x > 0 && box.x + box.width < grey.cols) {  // Wholly in the view: 1/10 x 1/2 of it.
        EXPECT_NEAR(box.width, 6.4, 2.0);
        EXPECT_NEAR(box.height, 16.0, 2.0);
      }
    }
    ASSERT_GE(centres.size(), static_cast<std::size_t>(length) * 3 / 4) << "the figure is in most of the stop";
    const bool rightwards = centres.back() > centres.front();
    for (std::size_t k = 1; k < centres.size(); ++k) {
      EXPECT_EQ(centres[k] > centres[k - 1], rightwards) << "the figure walks on at stopped frame " << k;
    }
    // From one side of the 64 px view to the other.
    EXPECT_LT(std::min(centres.front(), centres.back()), 6.0);
    EXPECT_GT(std::max(centres.front(), centres.back()), 58.0);
  }
}

TEST(CameraDrive, AStandingCameraAddsNoiseOfHalfAGreyLevelAndAGainWithinTwoPercentScaledWithTheWidth) {
  for (const int width : {64, 256}) {
    SCOPED_TRACE("width " + std::to_string(width));
    const std::vector<cv::Mat> route = flatRoute(100, width);
    CameraDriveSettings settings = smallDrive();
    settings.stops = 0;
    settings.fast_frames = 0;
    const CameraDrive drive(100, settings);
    double variance = 0.0;
    int copies = 0;
    for (int i = 0; i < drive.size(); ++i) {
      const DriveFrame& frame = drive.frames()[static_cast<std::size_t>(i)];
      if (frame.kind != DriveFrameKind::kSlowCopy) continue;
      const cv::Mat& original = route[static_cast<std::size_t>(frame.route_frame)];
      cv::Mat difference;
      drive.render(i, original).convertTo(difference, CV_64F);
      cv::Mat base;
      original.convertTo(base, CV_64F);
      difference -= base;
      cv::Scalar mean;
      cv::Scalar deviation;
      cv::meanStdDev(difference.reshape(1), mean, deviation);
      const double level = base.at<cv::Vec3d>(0, 0)[0];
      EXPECT_LE(std::abs(mean[0]), 0.02 * level + 0.1) << "gain beyond 2% at drive frame " << i;
      variance += deviation[0] * deviation[0];
      ++copies;
    }
    ASSERT_EQ(copies, settings.slow_frames);
    // Rounding to whole grey levels adds 1/12 to the variance; the gain spread adds a little.
    const double expected = 0.5 * width / 64.0;
    EXPECT_NEAR(std::sqrt(variance / copies), std::sqrt(expected * expected + 1.0 / 12.0), 0.15 * expected + 0.1);
  }
}

TEST(CameraDrive, BadSettingsAndRoutesTooShortAreRefusedByName) {
  CameraDriveSettings settings;
  settings.stop_frames_max = 10;
  EXPECT_NE(invalidArgumentMessage([&] {
              CameraDrive(1000, settings);
            }).find("stop_frames_max must be >= stop_frames_min (30), got 10"),
            std::string::npos);
  settings = CameraDriveSettings{};
  settings.noise_std = 0.0;
  EXPECT_NE(invalidArgumentMessage([&] { CameraDrive(1000, settings); }).find("noise_std must be in (0, 100], got 0"),
            std::string::npos);
  // A drive is held in memory: a stop of 10^8 frames grew to 15 GB before it was refused.
  settings = CameraDriveSettings{};
  settings.stop_frames_max = 100000000;
  EXPECT_NE(invalidArgumentMessage([&] { CameraDrive(1000, settings); })
                .find("stop_frames_max must be <= 100000, got 100000000"),
            std::string::npos);
  settings = CameraDriveSettings{};
  settings.stops = 5000;
  EXPECT_NE(invalidArgumentMessage([&] { CameraDrive(1000, settings); }).find("stops must be in 0..1000, got 5000"),
            std::string::npos);
  settings = CameraDriveSettings{};
  settings.vibration = 2.0;
  EXPECT_NE(invalidArgumentMessage([&] { CameraDrive(1000, settings); }).find("vibration"), std::string::npos);
  EXPECT_NE(invalidArgumentMessage([&] { CameraDrive(150, CameraDriveSettings{}); })
                .find("a route of 150 frames cannot hold a half-speed stretch of 100, a double-speed stretch of 100"),
            std::string::npos);
  const CameraDrive drive(300);
  EXPECT_THROW(drive.render(drive.size(), cv::Mat(32, 64, CV_8UC1)), std::out_of_range);
  EXPECT_NE(invalidArgumentMessage([&] { drive.render(0, cv::Mat(32, 64, CV_16UC1)); }).find("8-bit"),
            std::string::npos);
  EXPECT_NE(invalidArgumentMessage([&] { renderDrive(drive, flatRoute(10)); })
                .find("planned for 300 route frames, but the route has 10 images"),
            std::string::npos);
}

TEST(CameraDrive, FrameKindsHaveNames) {
  for (const DriveFrameKind kind : {DriveFrameKind::kMoving, DriveFrameKind::kStopped, DriveFrameKind::kSlowCopy}) {
    EXPECT_EQ(parseDriveFrameKind(toString(kind)), kind);
  }
  EXPECT_THROW(parseDriveFrameKind("parked"), std::invalid_argument);
}

TEST(DriveGroundTruth, AQueryFrameMatchesTheReferenceFramesOfItsRouteFrameWithinTheTolerance) {
  // Reference: route frames 0 1 2 2 2 3 5 7 (a stop at 2, double speed from 3); query: 0 2 4 6 6.
  const std::vector<int> reference = {0, 1, 2, 2, 2, 3, 5, 7};
  const std::vector<int> query = {0, 2, 4, 6, 6};
  const GroundTruth exact = driveGroundTruth(reference, query, 0);
  EXPECT_EQ(exact.at(0), (std::vector<int>{0}));
  EXPECT_EQ(exact.at(1), (std::vector<int>{2, 3, 4}));
  EXPECT_TRUE(exact.at(2).empty());  // Route frame 4 was left out of the reference drive.
  const GroundTruth near = driveGroundTruth(reference, query, 1);
  EXPECT_EQ(near.at(2), (std::vector<int>{5, 6}));
  EXPECT_EQ(near.at(3), (std::vector<int>{6, 7}));
  EXPECT_EQ(near.size(), query.size());
  // The largest tolerance takes in every reference frame (it wrapped round before).
  const GroundTruth everything = driveGroundTruth(reference, query, std::numeric_limits<int>::max());
  for (const auto& [frame, matches] : everything) EXPECT_EQ(matches.size(), reference.size()) << frame;
  EXPECT_THROW(driveGroundTruth(reference, query, -1), std::invalid_argument);
}

TEST(CameraDrive, AStopOfNoFramesIsRefused) {
  CameraDriveSettings settings;
  settings.stop_frames_min = 0;
  EXPECT_NE(invalidArgumentMessage([&] { CameraDrive(1000, settings); }).find("stop_frames_min must be >= 1, got 0"),
            std::string::npos);
  settings.stops = 0;  // without stops their length does not matter
  EXPECT_NO_THROW(CameraDrive(1000, settings));
}

TEST(CameraDrive, StretchesOfDifferentLengthsLieApartWithinTheRoute) {
  for (std::uint64_t seed = 0; seed < 40; ++seed) {
    CameraDriveSettings settings;
    settings.seed = seed;
    settings.stops = 0;
    settings.slow_frames = 30;
    settings.fast_frames = 10;
    const CameraDrive drive(100, settings);
    const int slow_end = drive.slowBegin() + settings.slow_frames;
    const int fast_end = drive.fastBegin() + settings.fast_frames;
    EXPECT_TRUE(slow_end <= drive.fastBegin() || fast_end <= drive.slowBegin()) << "seed " << seed;
    EXPECT_LE(std::max(slow_end, fast_end), 100) << "seed " << seed;
    // Every route frame once, those of the slow stretch twice, every other one of the fast stretch.
    EXPECT_EQ(drive.size(), 100 + 30 - 5) << "seed " << seed;
  }
}

}  // namespace
}  // namespace mrs_vpr
