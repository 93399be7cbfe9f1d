#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "mrs_vpr/appearance_keyframes.hpp"
#include "mrs_vpr/descriptor.hpp"
#include "mrs_vpr/place_recognizer.hpp"
#include "mrs_vpr/repeated_views.hpp"
#include "mrs_vpr/synthetic_route.hpp"
#include "support/front_ends.hpp"

namespace mrs_vpr {
namespace {

using testing_support::thumbnailParams;

/// A wide textured strip: a camera looking at it from x sees columns [x, x + 160).
cv::Mat panorama() {
  static const cv::Mat strip = [] {
    cv::Mat image(120, 6000, CV_8UC1);
    cv::RNG(11).fill(image, cv::RNG::UNIFORM, 0, 256);
    cv::GaussianBlur(image, image, cv::Size(0, 0), 4.0);
    cv::normalize(image, image, 0, 255, cv::NORM_MINMAX);
    return image;
  }();
  return strip;
}

/// The camera's view at x (sub-pixel), with a gain and sensor noise.
cv::Mat viewAt(double x, double gain, double noise, cv::RNG& rng) {
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, -x, 0, 1, 0);
  cv::Mat view;
  cv::warpAffine(panorama(), view, shift, cv::Size(160, 120), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  cv::Mat noisy(view.size(), CV_32F);
  rng.fill(noisy, cv::RNG::NORMAL, 0.0, noise);
  cv::Mat result;
  cv::addWeighted(view, gain, noisy, 1.0, 0.0, result, CV_8U);
  return result;
}

/// Keyframes chosen among `views` (each offered in turn).
int keyframesOf(AppearanceKeyframes& keyframes, const DescriptorExtractor& extractor,
                const std::vector<cv::Mat>& views) {
  int kept = 0;
  for (const cv::Mat& view : views) {
    if (keyframes.offer(extractor.compute(view))) ++kept;
  }
  return kept;
}

/// A drive along the strip at `speed` pixels a frame for `frames` frames, from x.
std::vector<cv::Mat> drive(double from, double speed, int frames, cv::RNG& rng) {
  std::vector<cv::Mat> views;
  for (int i = 0; i < frames; ++i) views.push_back(viewAt(from + speed * i, 1.0, 1.0, rng));
  return views;
}

/// Keyframes at a change of 0.4 whose scale (unrelated views) comes from a drive along the strip.
AppearanceKeyframes keyframesScaledByADrive(const DescriptorExtractor& extractor, const DescriptorParams& params,
                                            cv::RNG& rng) {
  AppearanceKeyframes keyframes(params, 0.4);
  keyframesOf(keyframes, extractor, drive(0.0, 12.0, 150, rng));
  return keyframes;
}

class AppearanceKeyframesTest : public ::testing::TestWithParam<DescriptorParams> {};

TEST_P(AppearanceKeyframesTest, AStopAddsNoKeyframeWhateverItsNoiseAndGain) {
  const DescriptorExtractor extractor(GetParam());
  cv::RNG rng(1);
  AppearanceKeyframes keyframes = keyframesScaledByADrive(extractor, GetParam(), rng);
  std::vector<cv::Mat> standing;
  for (int i = 0; i < 200; ++i) {
    // Sub-pixel vibration, a gain of +-2% and sensor noise, never an exact copy.
    standing.push_back(viewAt(1800.0 + rng.uniform(-0.3, 0.3), rng.uniform(0.98, 1.02), 2.0, rng));
  }
  EXPECT_EQ(keyframesOf(keyframes, extractor, standing), 1);  // The first view there, no other.
}

TEST_P(AppearanceKeyframesTest, ARobotStandingFromTheStartAddsOneKeyframe) {
  const DescriptorExtractor extractor(GetParam());
  AppearanceKeyframes keyframes(GetParam(), 0.4);
  cv::RNG rng(2);
  std::vector<cv::Mat> standing;
  for (int i = 0; i < 100; ++i) standing.push_back(viewAt(rng.uniform(-0.3, 0.3), rng.uniform(0.98, 1.02), 2.0, rng));
  EXPECT_EQ(keyframesOf(keyframes, extractor, standing), 1);
}

TEST_P(AppearanceKeyframesTest, AFrameOfASlowerRobotIsLessOftenAKeyframe) {
  const DescriptorExtractor extractor(GetParam());
  cv::RNG rng(3);
  AppearanceKeyframes fast(GetParam(), 0.4);
  AppearanceKeyframes slow(GetParam(), 0.4);
  // The same 600 pixels of the strip, in 300 frames and in 600.
  const int fast_keyframes = keyframesOf(fast, extractor, drive(0.0, 2.0, 300, rng));
  const int slow_keyframes = keyframesOf(slow, extractor, drive(0.0, 1.0, 600, rng));
  EXPECT_GT(fast_keyframes, 20);
  EXPECT_LT(fast_keyframes, 300);  // Not every frame: neighbours overlap.
  // About as many keyframes for the same ground, so half as many per frame at half the speed.
  EXPECT_NEAR(static_cast<double>(slow_keyframes) / fast_keyframes, 1.0, 0.35);
}

TEST_P(AppearanceKeyframesTest, ASmoothRouteKeepsItsKeyframesFewPlacesApart) {
  // The generated route drifts slowly and smoothly from place to place: frames moving away from the
  // last keyframe must not drag the view they are compared with along (which left 130 places between
  // two keyframes).
  SyntheticRouteParams route_params;
  route_params.reference_frames = 600;
  route_params.image_width = 320;
  route_params.image_height = 160;
  const SyntheticRoute route = generateSyntheticRoute(route_params);
  const DescriptorExtractor extractor(GetParam());
  AppearanceKeyframes keyframes(GetParam(), 0.4);
  int last_kept = 0;
  int largest_gap = 0;
  for (int i = 0; i < static_cast<int>(route.reference.size()); ++i) {
    const cv::Mat descriptor = extractor.compute(route.reference[static_cast<std::size_t>(i)]);
    if (keyframes.wants(descriptor)) {
      keyframes.keep(descriptor);
      largest_gap = std::max(largest_gap, i - last_kept);
      last_kept = i;
    } else {
      keyframes.skip(descriptor);
    }
  }
  // And the route's end: a rule that stopped keeping frames would leave its gap there.
  largest_gap = std::max(largest_gap, static_cast<int>(route.reference.size()) - 1 - last_kept);
  EXPECT_LE(largest_gap, 15);
}

TEST_P(AppearanceKeyframesTest, OneFrameWithoutThePlacesStructureDoesNotStopTheNextKeyframes) {
  // A camera starting up, an exposure glitch, a covered lens, a text overlay on black: such a frame
  // (HOG zero or one orientation) became a keyframe whose own distance to noise set the scale, and
  // the frames after it stayed below min_change (none of 150 real Nordland frames after 21
  // keyframes became a keyframe).
  const DescriptorExtractor extractor(GetParam());
  cv::Mat gradient(120, 160, CV_8UC1);
  for (int x = 0; x < gradient.cols; ++x) gradient.col(x).setTo(x * 60 / gradient.cols);
  cv::Mat overlay(120, 160, CV_8UC1, cv::Scalar(0));
  cv::putText(overlay, "12:00:01", cv::Point(5, 20), cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(255));
  const std::vector<cv::Mat> blanks = {cv::Mat(120, 160, CV_8UC1, cv::Scalar(0)),
                                       cv::Mat(120, 160, CV_8UC1, cv::Scalar(128)), gradient, overlay};
  for (std::size_t i = 0; i < blanks.size(); ++i) {
    cv::RNG rng(12);
    AppearanceKeyframes keyframes(GetParam(), 0.4);
    AppearanceKeyframes without(GetParam(), 0.4);
    const std::vector<cv::Mat> before = drive(0.0, 12.0, 40, rng);
    const std::vector<cv::Mat> after = drive(480.0, 12.0, 60, rng);
    const int kept_before = keyframesOf(keyframes, extractor, before);
    ASSERT_EQ(keyframesOf(without, extractor, before), kept_before);
    ASSERT_LT(kept_before, AppearanceKeyframes::kUnrelatedGap);  // The stand-in still sets the scale.
    keyframes.offer(extractor.compute(blanks[i]));
    const int kept_after = keyframesOf(keyframes, extractor, after);
    const int kept_after_without = keyframesOf(without, extractor, after);
    EXPECT_GE(kept_after, kept_after_without - 1) << "frame " << i;
  }
}

TEST_P(AppearanceKeyframesTest, AViewAmongTheRecentKeyframesIsNotNewAgain) {
  const DescriptorExtractor extractor(GetParam());
  cv::RNG rng(6);
  AppearanceKeyframes keyframes = keyframesScaledByADrive(extractor, GetParam(), rng);
  // A camera that swings between two views (a flickering light, a gate opening and closing): each
  // switch changes the view by far more than min_change, but both views are already keyframes.
  std::vector<cv::Mat> swinging;
  for (int i = 0; i < 40; ++i) swinging.push_back(viewAt(i % 2 == 0 ? 2400.0 : 2800.0, 1.0, 1.0, rng));
  EXPECT_EQ(keyframesOf(keyframes, extractor, swinging), 2);
  // A follower (another camera's traversal on this scale) compares with its newest keyframe only.
  AppearanceKeyframes follower = keyframes.follower();
  EXPECT_EQ(keyframesOf(follower, extractor, swinging), 40);
  // Once more than kRecentKeyframes other keyframes came, the first view is new again (a revisit).
  std::vector<cv::Mat> away;
  for (int i = 0; i <= AppearanceKeyframes::kRecentKeyframes; ++i)
    away.push_back(viewAt(3200.0 + 400.0 * i, 1, 1, rng));
  EXPECT_EQ(keyframesOf(keyframes, extractor, away), AppearanceKeyframes::kRecentKeyframes + 1);
  EXPECT_EQ(keyframesOf(keyframes, extractor, {viewAt(2400.0, 1.0, 1.0, rng)}), 1);
}

TEST_P(AppearanceKeyframesTest, ZeroKeepsEveryFrameAndResetForgetsTheLastKeyframe) {
  const DescriptorExtractor extractor(GetParam());
  cv::RNG rng(4);
  AppearanceKeyframes every(GetParam(), 0.0);
  EXPECT_FALSE(every.enabled());
  EXPECT_EQ(keyframesOf(every, extractor, std::vector<cv::Mat>(5, viewAt(0, 1, 0, rng))), 5);
  AppearanceKeyframes keyframes(GetParam(), 0.4);
  EXPECT_EQ(keyframesOf(keyframes, extractor, std::vector<cv::Mat>(3, viewAt(0, 1, 0, rng))), 1);
  keyframes.reset();
  EXPECT_EQ(keyframesOf(keyframes, extractor, std::vector<cv::Mat>(3, viewAt(0, 1, 0, rng))), 1);
}

TEST_P(AppearanceKeyframesTest, TheScaleBecomesTheDataOwnOnceKeyframesAreFarEnoughApart) {
  const DescriptorExtractor extractor(GetParam());
  AppearanceKeyframes keyframes(GetParam(), 0.4);
  cv::RNG rng(5);
  const cv::Mat first = extractor.compute(viewAt(0, 1, 1, rng));
  keyframes.keep(first);
  const double stand_in = keyframes.scale();
  EXPECT_GT(stand_in, 0.0);
  // Views 400 px apart share nothing: as keyframes, their pairs 50 apart give the scale.
  for (int i = 1; i <= AppearanceKeyframes::kUnrelatedGap + AppearanceKeyframes::kMinScaleSamples; ++i) {
    keyframes.keep(extractor.compute(viewAt(400.0 * i, 1, 1, rng)));
  }
  EXPECT_NE(keyframes.scale(), stand_in);
  EXPECT_NEAR(keyframes.scale(), stand_in, 0.5 * stand_in);  // Both are unrelated views.
}

TEST_P(AppearanceKeyframesTest, KeyframesOfOneViewLeaveTheStandInNotAScaleOfZero) {
  // Keyframes of a covered camera, taken by travel or loaded from a map: their pairs kUnrelatedGap
  // apart differ by nothing. A scale of 0 would read every later change as none, for good.
  const DescriptorExtractor extractor(GetParam());
  AppearanceKeyframes keyframes(GetParam(), 0.4);
  const cv::Mat covered = extractor.compute(cv::Mat(120, 160, CV_8UC1, cv::Scalar(0)));
  for (int i = 0; i < AppearanceKeyframes::kUnrelatedGap + AppearanceKeyframes::kScaleSamples; ++i) {
    keyframes.keep(covered);
  }
  EXPECT_GT(keyframes.scale(), 0.0);
  cv::RNG rng(7);
  EXPECT_GT(keyframesOf(keyframes, extractor, drive(0.0, 12.0, 50, rng)), 10);
}

TEST_P(AppearanceKeyframesTest, AStandingCamerasNoiseAveragesOutOfTheReference) {
  // A clean keyframe, then a standing camera whose noise (up to 16 grey levels) changes its HOG
  // descriptor by about 0.75 of min_change. Once the noisy frames join the reference, a frame is
  // compared with their mean, which lies closer to it than the keyframe (with the frames that joined
  // only within half of min_change, the median change was 0.41 against 0.30).
  const DescriptorExtractor extractor(GetParam());
  cv::RNG rng(1);
  AppearanceKeyframes keyframes = keyframesScaledByADrive(extractor, GetParam(), rng);
  ASSERT_EQ(keyframesOf(keyframes, extractor, {viewAt(1800.0, 1.0, 0.0, rng)}), 1);
  std::vector<double> changes;
  for (int i = 0; i < 200; ++i) {
    const cv::Mat view = viewAt(1800.0 + rng.uniform(-0.3, 0.3), rng.uniform(0.98, 1.02), rng.uniform(0.0, 16.0), rng);
    keyframesOf(keyframes, extractor, {view});
    changes.push_back(keyframes.lastChange());
  }
  std::nth_element(changes.begin(), changes.begin() + 100, changes.end());
  EXPECT_LT(changes[100], 0.8 * 0.4);
}

INSTANTIATE_TEST_SUITE_P(FrontEnds, AppearanceKeyframesTest, ::testing::Values(DescriptorParams{}, thumbnailParams()),
                         [](const auto& info) { return info.param.type; });

TEST(AppearanceKeyframes, AStandingCamerasStrayLikeAFrameThatJoinedTheReferenceIsNotAKeyframe) {
  // Descriptors by hand in HOG's layout (regions of 4 x 9 bytes), so that each distance is exact. In
  // units of min_change, the joined frame lies 1/3 from the keyframe; the stray lies 8/9 from the
  // joined frame, 1.22 from the keyframe (within kStrayShare) and 1.06 from the reference (their mean).
  const DescriptorParams params;
  const DescriptorExtractor extractor(params);
  // Both recognisers learn the same scale from the same drive.
  const auto scaled = [&] {
    cv::RNG rng(5);
    return keyframesScaledByADrive(extractor, params, rng);
  };
  AppearanceKeyframes keyframes = scaled();
  const int region = 4 * params.hog_bins;
  const auto descriptor = [&](double joined_offset, double stray_offset) {
    cv::Mat bytes(1, params.descriptorSize(), CV_8UC1, cv::Scalar(40));
    for (int i = 0; i < bytes.cols; ++i) {
      if (i % region < 4) bytes.at<std::uint8_t>(i) = cv::saturate_cast<std::uint8_t>(40 + joined_offset);
      if (i % region >= region - 4) bytes.at<std::uint8_t>(i) = cv::saturate_cast<std::uint8_t>(40 + stray_offset);
    }
    return bytes;
  };
  const cv::Mat keyframe = descriptor(0.0, 0.0);
  ASSERT_TRUE(keyframes.wants(keyframe));
  keyframes.keep(keyframe);
  // Four bytes of 36 changed by 9 x d change the region by d.
  const double min_change = 0.4 * keyframes.scale();
  ASSERT_LT(40 + 9 * min_change, 255.0);
  const cv::Mat joined = descriptor(9 * min_change / 3, 0.0);
  ASSERT_FALSE(keyframes.wants(joined));
  keyframes.skip(joined);
  const cv::Mat stray = descriptor(9 * min_change / 3, 9 * min_change * 8 / 9);
  EXPECT_FALSE(keyframes.wants(stray));
  EXPECT_GT(keyframes.lastChange(), 0.4);  // Over min_change from the reference: the joined frame keeps it out.
  EXPECT_FALSE(keyframes.lastSeenBefore());
  // The joined frame shows the keyframe's view itself; the stray, refused, does not stand there.
  EXPECT_FALSE(keyframes.lastStood());
  const cv::Mat between = descriptor(9 * min_change / 3, 9 * min_change * 0.8);  // 0.97 from the reference
  EXPECT_FALSE(keyframes.wants(between));
  EXPECT_FALSE(keyframes.lastStood());
  EXPECT_FALSE(keyframes.wants(joined));
  EXPECT_TRUE(keyframes.lastStood());
  // Without the joined frame the same view is new.
  AppearanceKeyframes without = scaled();
  ASSERT_TRUE(without.wants(keyframe));
  without.keep(keyframe);
  EXPECT_TRUE(without.wants(stray));
}

TEST(AppearanceKeyframes, TheReferenceOfACameraStandingForDaysIsItsView) {
  // A parked robot's camera: every frame joins the reference. Summed in floats, the reference drifted
  // off the view it stood at once its sums passed 2^24 (a few hundred thousand frames), rounding every
  // byte the same way frame after frame: by 1.3 grey levels here after a million frames (9 hours at
  // 30 Hz), 0.05 of the scale.
  const DescriptorParams params;
  cv::RNG rng(5);
  AppearanceKeyframes keyframes = keyframesScaledByADrive(DescriptorExtractor(params), params, rng);
  const cv::Mat view(1, params.descriptorSize(), CV_8UC1, cv::Scalar(100));
  ASSERT_TRUE(keyframes.wants(view));
  keyframes.keep(view);
  ASSERT_FALSE(keyframes.wants(view));  // What offer() asks before each skip(), the same every frame.
  for (int frame = 0; frame < 1'000'000; ++frame) keyframes.skip(view);
  EXPECT_FALSE(keyframes.wants(view));
  EXPECT_LT(keyframes.lastChange(), 1e-6);  // the mean's last rounding, not a drift
}

TEST(PlaceRecognizer, AViewLikeAnOlderKeyframeIsSeenRecentlyNotTooSimilar) {
  // The node restates closures only for frames too similar to the newest keyframe: a frame that looks
  // like an older one (a robot swinging back) must say so.
  PlaceRecognizer recognizer;
  cv::RNG rng(8);
  for (int i = 0; i < 150; ++i) recognizer.addFrame(viewAt(12.0 * i, 1, 1, rng));  // the scale
  ASSERT_EQ(recognizer.addFrame(viewAt(2400.0, 1, 1, rng)), FrameAdmission::kAdmitted);
  ASSERT_EQ(recognizer.addFrame(viewAt(2800.0, 1, 1, rng)), FrameAdmission::kAdmitted);
  EXPECT_EQ(recognizer.addFrame(viewAt(2800.0, 1, 1, rng)), FrameAdmission::kTooSimilar);
  EXPECT_EQ(recognizer.addFrame(viewAt(2400.0, 1, 1, rng)), FrameAdmission::kSeenRecently);
}

TEST(PlaceRecognizer, OnlyAFrameAtTheNewestKeyframesOwnViewStood) {
  // The node restates a keyframe's closures for the frames that stood at its view: those within
  // kReferenceShare of min_change of its reference, not those on their way to the next place.
  PlaceRecognizer recognizer;
  cv::RNG rng(9);
  for (int i = 0; i < 150; ++i) recognizer.addFrame(viewAt(12.0 * i, 1, 1, rng));  // the scale
  ASSERT_EQ(recognizer.addFrame(viewAt(3000.0, 1, 1, rng)), FrameAdmission::kAdmitted);
  const double stood_below = AppearanceKeyframes::kReferenceShare * RecognizerParams{}.min_appearance_change;
  int stood = 0;
  int on_its_way = 0;
  // A camera creeping on from the keyframe, a tenth of a pixel a frame, until a keyframe comes.
  for (double x = 3000.1; recognizer.addFrame(viewAt(x, 1, 1, rng)) == FrameAdmission::kTooSimilar; x += 0.1) {
    const bool expected = recognizer.lastAppearanceChange() < stood_below;
    EXPECT_EQ(recognizer.lastFrameStood(), expected) << "change " << recognizer.lastAppearanceChange();
    ++(expected ? stood : on_its_way);
  }
  EXPECT_GT(stood, 0);
  EXPECT_GT(on_its_way, 0);
}

TEST(PlaceRecognizer, KeyframesFramesByAppearanceButTakesDescriptorsAsKeyframes) {
  PlaceRecognizer recognizer;
  cv::RNG rng(6);
  const cv::Mat view = viewAt(100, 1, 1, rng);
  EXPECT_EQ(recognizer.addFrame(view), FrameAdmission::kAdmitted);
  EXPECT_EQ(recognizer.addFrame(viewAt(100.2, 1.01, 1, rng)), FrameAdmission::kTooSimilar);
  EXPECT_GT(recognizer.lastAppearanceChange(), 0.0);
  EXPECT_EQ(recognizer.addFrame(viewAt(700, 1, 1, rng)), FrameAdmission::kAdmitted);
  // A saved map's frames are keyframes already.
  EXPECT_EQ(recognizer.addDescriptor(recognizer.describe(view)), FrameAdmission::kAdmitted);
  EXPECT_EQ(recognizer.size(), 3);
  RecognizerParams every_frame;
  every_frame.min_appearance_change = 0.0;
  PlaceRecognizer all(Parameters{}, every_frame);
  EXPECT_EQ(all.addFrame(view), FrameAdmission::kAdmitted);
  EXPECT_EQ(all.addFrame(view), FrameAdmission::kAdmitted);
}

/// Descriptors of `views`, as a test sequence.
DescriptorSequence sequenceOf(const DescriptorExtractor& extractor, const std::vector<cv::Mat>& views) {
  DescriptorSequence sequence(extractor.size());
  for (const cv::Mat& view : views) sequence.append(extractor.compute(view));
  return sequence;
}

/// A camera standing in the dark: the strip's view at x at 1% of its light, with sensor noise and
/// vibration. HOG's block normalisation amplifies the noise until many of its frames pass the change.
std::vector<cv::Mat> darkStop(double x, int frames, cv::RNG& rng) {
  std::vector<cv::Mat> views;
  for (int i = 0; i < frames; ++i) views.push_back(viewAt(x + rng.uniform(-0.3, 0.3), 0.01, 2.0, rng));
  return views;
}

/// Keyframes on the default front end (HOG), scaled by a drive along the strip.
AppearanceKeyframes hogKeyframes(const DescriptorExtractor& extractor, cv::RNG& rng) {
  return keyframesScaledByADrive(extractor, DescriptorParams{}, rng);
}

TEST(RepeatedViews, AStandingCameraInTheDarkRepeatsOneViewThoughItsNoiseMakesKeyframes) {
  const DescriptorExtractor extractor{DescriptorParams{}};
  cv::RNG rng(3);
  const AppearanceKeyframes keyframes = hogKeyframes(extractor, rng);
  AppearanceKeyframes standing = keyframes;
  EXPECT_GT(keyframesOf(standing, extractor, darkStop(2500.0, 60, rng)), 10);  // what the rule is for
  EXPECT_TRUE(RepeatedViews(keyframes).mostlyRepeated(sequenceOf(extractor, darkStop(2500.0, 20, rng)).view()));
  // A long sequence is judged on a sample of its keyframes.
  const DescriptorSequence long_stop = sequenceOf(extractor, darkStop(2500.0, 4 * RepeatedViews::kMaxJudged, rng));
  EXPECT_TRUE(RepeatedViews(keyframes).mostlyRepeated(long_stop.view()));
}

TEST(RepeatedViews, AMovingCameraRepeatsNoView) {
  const DescriptorExtractor extractor{DescriptorParams{}};
  cv::RNG rng(4);
  const AppearanceKeyframes keyframes = hogKeyframes(extractor, rng);
  EXPECT_FALSE(RepeatedViews(keyframes).mostlyRepeated(sequenceOf(extractor, drive(2000.0, 12.0, 40, rng)).view()));
  // A sequence that stands in the dark for a third of its keyframes still shows mostly distinct views.
  std::vector<cv::Mat> partly = drive(2000.0, 12.0, 14, rng);
  for (const cv::Mat& view : darkStop(2168.0, 6, rng)) partly.push_back(view);
  EXPECT_FALSE(RepeatedViews(keyframes).mostlyRepeated(sequenceOf(extractor, partly).view()));
}

// "Mostly" is more than half: a sequence that stands for exactly half its keyframes is still judged
// on its views. The stop comes first, as judging ends once the distinct views reach half.
TEST(RepeatedViews, ASequenceHalfOfOneViewIsNotMostlyRepeated) {
  const DescriptorExtractor extractor{DescriptorParams{}};
  cv::RNG rng(7);
  const AppearanceKeyframes keyframes = hogKeyframes(extractor, rng);
  std::vector<cv::Mat> half = darkStop(2500.0, 10, rng);
  for (const cv::Mat& view : drive(2000.0, 12.0, 10, rng)) half.push_back(view);
  EXPECT_FALSE(RepeatedViews(keyframes).mostlyRepeated(sequenceOf(extractor, half).view()));
}

/// Keyframes of `size` bytes, each of one value throughout: two differ by the difference of their values.
DescriptorSequence flatKeyframes(int size, const std::vector<int>& values) {
  DescriptorSequence sequence(size);
  for (int value : values) sequence.append(cv::Mat(1, size, CV_8UC1, cv::Scalar(value)));
  return sequence;
}

/// What two keyframes showing one view differ by at most, as RepeatedViews measures it on `keyframes`.
double sameView(const AppearanceKeyframes& keyframes) {
  return AppearanceKeyframes::kStrayShare * keyframes.minChange() * keyframes.scale();
}

// RepeatedViews::kMinGap, written out: the sequences below are built for a gap of 3 keyframes.
constexpr int kGap = 3;

// A slow camera's keyframes one and two apart look alike, but it moves on: they are not compared,
// or every slow drive would be refused as a stop.
TEST(RepeatedViews, KeyframesCloserThanTheMinimumGapAreNotComparedAsOneView) {
  const DescriptorExtractor extractor{DescriptorParams{}};
  cv::RNG rng(8);
  const AppearanceKeyframes keyframes = hogKeyframes(extractor, rng);
  const double same_view = sameView(keyframes);
  // Each keyframe moves on by `step`: within one view of its neighbours closer than kGap only.
  const int step = static_cast<int>(std::ceil(same_view / kGap + 0.1));
  ASSERT_LT((kGap - 1) * step, same_view);
  ASSERT_GT(kGap * step, same_view);
  std::vector<int> slow;
  for (int i = 0; i < 12; ++i) slow.push_back(20 + i * step);
  ASSERT_LE(slow.back(), 255);
  EXPECT_FALSE(RepeatedViews(keyframes).mostlyRepeated(flatKeyframes(extractor.size(), slow).view()));
}

// Keyframes exactly kGap apart are compared: a view shown again after two others (A B C A B) is a
// repeat of most of the sequence, though no other pair of its keyframes is alike.
TEST(RepeatedViews, KeyframesExactlyTheMinimumGapApartAreCompared) {
  const DescriptorExtractor extractor{DescriptorParams{}};
  cv::RNG rng(9);
  const AppearanceKeyframes keyframes = hogKeyframes(extractor, rng);
  const int apart = static_cast<int>(std::ceil(2.0 * sameView(keyframes)));
  ASSERT_LE(20 + 2 * apart, 255);
  const int a = 20;
  const int b = a + apart;
  const int c = b + apart;
  EXPECT_TRUE(RepeatedViews(keyframes).mostlyRepeated(flatKeyframes(extractor.size(), {a, b, c, a, b}).view()));
}

// A sequence of at most kGap keyframes has no pair far enough apart to compare, however alike they
// are; an empty one is judged without dividing by its zero keyframes.
TEST(RepeatedViews, SequencesNoLongerThanTheMinimumGapRepeatNothing) {
  const DescriptorExtractor extractor{DescriptorParams{}};
  cv::RNG rng(10);
  const RepeatedViews views(hogKeyframes(extractor, rng));
  EXPECT_FALSE(views.mostlyRepeated(flatKeyframes(extractor.size(), {}).view()));
  EXPECT_FALSE(views.mostlyRepeated(flatKeyframes(extractor.size(), std::vector<int>(kGap, 20)).view()));
}

TEST(RepeatedViews, JudgesNothingWithoutKeyframesByAppearance) {
  const DescriptorExtractor extractor{DescriptorParams{}};
  cv::RNG rng(5);
  const AppearanceKeyframes every_frame(DescriptorParams{}, 0.0);
  EXPECT_FALSE(RepeatedViews(every_frame).enabled());
  EXPECT_FALSE(RepeatedViews(every_frame).mostlyRepeated(sequenceOf(extractor, darkStop(2500.0, 20, rng)).view()));
}

TEST(RepeatedViews, RefusesOnlyAnAcceptedAnswerAboutRepeatedViews) {
  const DescriptorExtractor extractor{DescriptorParams{}};
  cv::RNG rng(6);
  const RepeatedViews views(hogKeyframes(extractor, rng));
  const DescriptorSequence stop = sequenceOf(extractor, darkStop(2500.0, 20, rng));
  const DescriptorSequence moving = sequenceOf(extractor, drive(2000.0, 12.0, 20, rng));
  Match accepted;
  accepted.reference_index = 40;
  accepted.confidence = 6.0F;
  accepted.accepted = true;
  Match about_the_stop = accepted;
  refuseRepeatedViews(about_the_stop, stop.view(), views);
  EXPECT_FALSE(about_the_stop.accepted);
  EXPECT_TRUE(about_the_stop.repeated_view);
  EXPECT_EQ(about_the_stop.reference_index, 40);  // the answer stays; only the verdict changes
  Match about_the_drive = accepted;
  refuseRepeatedViews(about_the_drive, moving.view(), views);
  EXPECT_TRUE(about_the_drive.accepted);
  EXPECT_FALSE(about_the_drive.repeated_view);
  Match refused = accepted;
  refused.accepted = false;
  refuseRepeatedViews(refused, stop.view(), views);
  EXPECT_FALSE(refused.repeated_view);  // not judged: nothing to take back
}

TEST(RepeatedViews, ContinuousModesQuestionAboutKeyframesOfOneViewIsNotAccepted) {
  // A camera drives up to x = 2400 and stands there while its noise makes keyframes (every frame is
  // kept), drives on, and the recording of the approach and the stop is played again: the newest 30
  // keyframes are 12 of the approach and 18 of one view, and they match the older ones exactly.
  RecognizerParams near_enough;
  near_enough.recent_exclusion = 0;  // the map is small: every older keyframe is searched
  PlaceRecognizer recognizer(Parameters{}, near_enough);
  const DescriptorExtractor& extractor = recognizer.extractor();
  cv::RNG rng(7);
  const auto keep = [&](const std::vector<cv::Mat>& views) {
    for (const cv::Mat& view : views) recognizer.addDescriptor(extractor.compute(view));
  };
  std::vector<cv::Mat> approach_and_stop = drive(2256.0, 12.0, 12, rng);
  for (int i = 0; i < 18; ++i) approach_and_stop.push_back(viewAt(2400.0, 1.0, 6.0, rng));
  keep(drive(0.0, 12.0, 188, rng));
  keep(approach_and_stop);
  keep(drive(2412.0, 12.0, 280, rng));
  keep(approach_and_stop);
  const PlaceAnswer answer = recognizer.matchRecent(30);
  EXPECT_NEAR(answer.match.reference_index, 188 + 15, 2);  // the older copy's middle keyframe
  EXPECT_GE(answer.match.confidence, 3.0F);  // distinct enough to pass the rest of the rule
  EXPECT_TRUE(answer.match.repeated_view);
  EXPECT_FALSE(answer.match.accepted);
  // The verdict follows the repeated view's refusal, in the node's words.
  EXPECT_EQ(answer.verdict.rfind("not accepted: most of the test sequence's keyframes show one view again", 0), 0U)
      << answer.verdict;
}

}  // namespace
}  // namespace mrs_vpr
