#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "mrs_vpr/descriptor.hpp"
#include "mrs_vpr/parameters.hpp"
#include "support/error_message.hpp"
#include "support/front_ends.hpp"

namespace mrs_vpr {
namespace {

using testing_support::thumbnailParams;

using testing_support::invalidArgumentMessage;

DescriptorParams paramsOf(int width, int height, int patch) {
  DescriptorParams params = thumbnailParams();
  params.image_width = width;
  params.image_height = height;
  params.patch_size = patch;
  return params;
}

/// Deterministic textured colour image.
cv::Mat colourImage(int width, int height, int seed) {
  cv::Mat image(height, width, CV_8UC3);
  cv::RNG rng(static_cast<std::uint64_t>(seed));
  rng.fill(image, cv::RNG::UNIFORM, 0, 256);
  cv::GaussianBlur(image, image, cv::Size(5, 5), 1.5);
  return image;
}

TEST(DescriptorExtractor, DefaultDescriptorIsOneContinuousRowOfWTimesHBytes) {
  const DescriptorExtractor extractor{thumbnailParams()};
  EXPECT_EQ(extractor.size(), 64 * 32);
  const cv::Mat descriptor = extractor.compute(colourImage(160, 90, 1));
  EXPECT_EQ(descriptor.type(), CV_8UC1);
  EXPECT_EQ(descriptor.rows, 1);
  EXPECT_EQ(descriptor.cols, 64 * 32);
  EXPECT_TRUE(descriptor.isContinuous());
}

TEST(DescriptorExtractor, RefusesImagesBeyondThePixelLimitBeforeConvertingThem) {
  const DescriptorExtractor extractor{thumbnailParams()};
  // One row keeps the test's own memory small; the limit counts pixels, whatever the shape.
  const cv::Mat largest(1, static_cast<int>(DescriptorExtractor::kMaxImagePixels), CV_8UC1, cv::Scalar(7));
  EXPECT_NO_THROW(extractor.compute(largest));
  const cv::Mat larger(1, static_cast<int>(DescriptorExtractor::kMaxImagePixels) + 1, CV_8UC1, cv::Scalar(7));
  try {
    extractor.compute(larger);
    FAIL() << "an image beyond the limit was described";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("25000001 x 1 pixels is larger than the 25000000 pixels allowed"),
              std::string::npos)
        << error.what();
  }
}

TEST(DescriptorExtractor, QuantisesZScoresAs128Plus32Z) {
  // The image already has the descriptor size, so only patch normalisation acts on it.
  const DescriptorExtractor extractor(paramsOf(4, 4, 2));
  const cv::Mat image = (cv::Mat_<std::uint8_t>(4, 4) << 10, 20, 50, 50,  //
                         30, 40, 50, 50,                                    //
                         0, 0, 0, 0,                                        //
                         0, 0, 0, 0);
  const cv::Mat descriptor = extractor.compute(image);
  ASSERT_EQ(descriptor.cols, 16);
  // Patch {10, 20; 30, 40}: mean 25, population std sqrt(125); z = -+1.342, -+0.447.
  // 128 + 32 z = 85.07, 113.69, 142.31, 170.93.
  EXPECT_EQ(descriptor.at<std::uint8_t>(0, 0), 85);
  EXPECT_EQ(descriptor.at<std::uint8_t>(0, 1), 114);
  EXPECT_EQ(descriptor.at<std::uint8_t>(0, 4), 142);
  EXPECT_EQ(descriptor.at<std::uint8_t>(0, 5), 171);
  // Constant patches: z = 0 -> 128.
  for (int i : {2, 3, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15}) {
    EXPECT_EQ(descriptor.at<std::uint8_t>(0, i), 128) << "pixel " << i;
  }
}

TEST(DescriptorExtractor, SaturatesBeyondFourStandardDeviations) {
  // One bright pixel in an 8 x 8 patch: z = 63 / sqrt(63) = 7.9 -> 255; the rest z = -1 / sqrt(63) -> 124.
  const DescriptorExtractor extractor(paramsOf(8, 8, 8));
  cv::Mat image(8, 8, CV_8UC1, cv::Scalar(0));
  image.at<std::uint8_t>(3, 5) = 200;
  const cv::Mat descriptor = extractor.compute(image);
  EXPECT_EQ(descriptor.at<std::uint8_t>(0, 3 * 8 + 5), 255);
  EXPECT_EQ(descriptor.at<std::uint8_t>(0, 0), 124);
}

TEST(DescriptorExtractor, SixteenBitImageGivesTheSameDescriptorAsItsEightBitOriginal) {
  const DescriptorExtractor extractor{thumbnailParams()};
  cv::Mat gray;
  cv::cvtColor(colourImage(128, 64, 2), gray, cv::COLOR_BGR2GRAY);
  cv::Mat wide;
  gray.convertTo(wide, CV_16U, 256.0);
  const cv::Mat from_wide = extractor.compute(wide);
  EXPECT_EQ(from_wide.type(), CV_8UC1);
  EXPECT_EQ(from_wide.cols, extractor.size());
  // Patch normalisation removes the scale; float rounding may move a value by one level.
  EXPECT_LE(cv::norm(from_wide, extractor.compute(gray), cv::NORM_INF), 1.0);
}

TEST(DescriptorExtractor, SixteenBitColourGivesTheDescriptorOfItsSixteenBitGrey) {
  for (const DescriptorParams& params : {thumbnailParams(), DescriptorParams{}}) {
    SCOPED_TRACE(params.type);
    const DescriptorExtractor extractor{params};
    const cv::Mat colour = colourImage(128, 64, 2);
    cv::Mat alpha;
    cv::cvtColor(colour, alpha, cv::COLOR_BGR2BGRA);
    for (const cv::Mat& eight_bit : {colour, alpha}) {
      cv::Mat wide;
      eight_bit.convertTo(wide, CV_16U, 257.0);  // 255 -> 65535, as a 16-bit PNG of the same picture
      cv::Mat wide_grey;
      cv::cvtColor(wide, wide_grey, eight_bit.channels() == 3 ? cv::COLOR_BGR2GRAY : cv::COLOR_BGRA2GRAY);
      const cv::Mat expected = extractor.compute(wide_grey);
      // Another picture in between: the grey buffer reused from frame to frame must not answer for it
      // (it did, when a 16-bit band was reallocated by cvtColor instead of written).
      const cv::Mat other = extractor.compute(colourImage(128, 64, 7));
      const cv::Mat from_wide = extractor.compute(wide);
      EXPECT_EQ(cv::norm(from_wide, expected, cv::NORM_INF), 0.0);
      EXPECT_GT(cv::norm(other, expected, cv::NORM_L1), 0.05 * expected.total());  // The check can fail.
      if (params.type == kThumbnailFrontEnd) {
        // The thumbnail normalises each patch, so the 8-bit original gives nearly the same values: its
        // grey levels, rounded to whole levels, are up to half a level off the 16-bit ones.
        const cv::Mat original = extractor.compute(eight_bit);
        EXPECT_LE(cv::norm(from_wide, original, cv::NORM_INF), 2.0);
        EXPECT_LE(cv::norm(from_wide, original, cv::NORM_L1), 0.5 * original.total());
      }
    }
  }
}

TEST(DescriptorExtractor, RgbOrderOfASwappedImageGivesTheBgrResult) {
  const DescriptorExtractor extractor{thumbnailParams()};
  const cv::Mat bgr = colourImage(128, 64, 3);
  cv::Mat rgb;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  const cv::Mat expected = extractor.compute(bgr, ChannelOrder::kBgr);
  EXPECT_EQ(cv::norm(extractor.compute(rgb, ChannelOrder::kRgb), expected, cv::NORM_INF), 0.0);
  // The channel order matters: reading the swapped image as BGR gives another descriptor.
  EXPECT_GT(cv::norm(extractor.compute(rgb, ChannelOrder::kBgr), expected, cv::NORM_L1), 0.0);
}

TEST(DescriptorExtractor, FourChannelImagesIgnoreAlphaAndHonourChannelOrder) {
  const DescriptorExtractor extractor{thumbnailParams()};
  const cv::Mat bgr = colourImage(128, 64, 4);
  cv::Mat bgra;
  cv::cvtColor(bgr, bgra, cv::COLOR_BGR2BGRA);
  // An alpha channel with structure must not change the descriptor.
  cv::Mat channels[4];
  cv::split(bgra, channels);
  cv::randu(channels[3], 0, 256);
  cv::merge(channels, 4, bgra);
  cv::Mat rgba;
  cv::cvtColor(bgra, rgba, cv::COLOR_BGRA2RGBA);
  const cv::Mat expected = extractor.compute(bgr);
  const cv::Mat from_bgra = extractor.compute(bgra, ChannelOrder::kBgr);
  EXPECT_EQ(from_bgra.type(), CV_8UC1);
  EXPECT_EQ(from_bgra.cols, extractor.size());
  EXPECT_EQ(cv::norm(from_bgra, expected, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(extractor.compute(rgba, ChannelOrder::kRgb), expected, cv::NORM_INF), 0.0);
}

TEST(ToGrey, ACameraFrameConvertedInBandsHasTheWholeConversionsPixels) {
  // 641 x 481: several bands of the conversion, the last one partial, and a non-continuous ROI.
  const cv::Mat big = colourImage(700, 500, 6);
  const cv::Mat frame = big(cv::Rect(13, 7, 641, 481));
  cv::Mat frame_with_alpha;
  cv::cvtColor(frame, frame_with_alpha, cv::COLOR_BGR2BGRA);
  const struct {
    const cv::Mat& image;
    ChannelOrder order;
    int code;
  } cases[] = {{frame, ChannelOrder::kBgr, cv::COLOR_BGR2GRAY},
               {frame, ChannelOrder::kRgb, cv::COLOR_RGB2GRAY},
               {frame_with_alpha, ChannelOrder::kBgr, cv::COLOR_BGRA2GRAY},
               {frame_with_alpha, ChannelOrder::kRgb, cv::COLOR_RGBA2GRAY}};
  for (const auto& conversion : cases) {
    cv::Mat expected;
    cv::cvtColor(conversion.image, expected, conversion.code);
    cv::Mat buffer;
    const cv::Mat& grey = toGrey(conversion.image, conversion.order, buffer);
    ASSERT_EQ(grey.type(), CV_8UC1);
    ASSERT_EQ(grey.size(), expected.size());
    EXPECT_EQ(cv::norm(grey, expected, cv::NORM_INF), 0.0) << "conversion code " << conversion.code;
  }
  // The buffer may be the image itself, as with cv::cvtColor.
  cv::Mat in_place = frame.clone();
  cv::Mat expected;
  cv::cvtColor(in_place, expected, cv::COLOR_BGR2GRAY);
  const cv::Mat& grey = toGrey(in_place, ChannelOrder::kBgr, in_place);
  ASSERT_EQ(grey.type(), CV_8UC1);
  EXPECT_EQ(cv::norm(grey, expected, cv::NORM_INF), 0.0);
}

TEST(DescriptorExtractor, NonContinuousRoiIsDescribedLikeItsCopy) {
  const DescriptorExtractor extractor{thumbnailParams()};
  const cv::Mat big = colourImage(200, 120, 5);
  const cv::Mat roi = big(cv::Rect(30, 20, 128, 64));
  ASSERT_FALSE(roi.isContinuous());
  EXPECT_EQ(cv::norm(extractor.compute(roi), extractor.compute(roi.clone()), cv::NORM_INF), 0.0);
}

TEST(DescriptorExtractor, EmptyImageThrowsNamingTheProblem) {
  const DescriptorExtractor extractor{thumbnailParams()};
  const std::string message = invalidArgumentMessage([&] { extractor.compute(cv::Mat()); });
  EXPECT_NE(message.find("empty"), std::string::npos) << message;
}

TEST(DescriptorExtractor, UnsupportedTypesThrowNamingTheType) {
  const DescriptorExtractor extractor{thumbnailParams()};
  const std::string float_message =
      invalidArgumentMessage([&] { extractor.compute(cv::Mat(64, 128, CV_32FC3, cv::Scalar::all(0.5))); });
  EXPECT_NE(float_message.find("unsupported image type"), std::string::npos) << float_message;
  EXPECT_NE(float_message.find("32FC3"), std::string::npos) << float_message;
  const std::string two_channel_message =
      invalidArgumentMessage([&] { extractor.compute(cv::Mat(64, 128, CV_8UC2, cv::Scalar::all(1))); });
  EXPECT_NE(two_channel_message.find("8UC2"), std::string::npos) << two_channel_message;
}

TEST(DescriptorExtractor, AnImageOfMoreThanTwoDimensionsThrows) {
  // OpenCV's resize would throw its own cv::Exception from deep inside the front end.
  const int sizes[] = {4, 64, 128};
  for (const DescriptorParams& params : {thumbnailParams(), DescriptorParams{}}) {
    const DescriptorExtractor extractor{params};
    const std::string message = invalidArgumentMessage([&] { extractor.compute(cv::Mat(3, sizes, CV_8UC1)); });
    EXPECT_NE(message.find("image has 3 dimensions, not 2"), std::string::npos) << message;
  }
}

TEST(DescriptorParams, AHogCellOfNoSizeIsRefusedNotDividedBy) {
  DescriptorParams params;
  params.hog_cell_size = 0;
  EXPECT_EQ(params.descriptorSize(), 0);
  const std::string message = invalidArgumentMessage([&] { params.validate(); });
  EXPECT_NE(message.find("descriptor/hog/cell_size"), std::string::npos) << message;
}

TEST(DescriptorExtractor, InvalidParametersThrowNamingTheParameter) {
  const std::string not_dividing = invalidArgumentMessage([] { DescriptorExtractor(paramsOf(64, 32, 5)); });
  EXPECT_NE(not_dividing.find("descriptor/patch_size"), std::string::npos) << not_dividing;
  const std::string narrow = invalidArgumentMessage([] { DescriptorExtractor(paramsOf(2, 32, 1)); });
  EXPECT_NE(narrow.find("descriptor/image_width"), std::string::npos) << narrow;
  const std::string tall = invalidArgumentMessage([] { DescriptorExtractor(paramsOf(64, 2048, 8)); });
  EXPECT_NE(tall.find("descriptor/image_height"), std::string::npos) << tall;
}

TEST(DescriptorExtractor, SameImageSameDescriptorAndDifferentImagesDiffer) {
  const DescriptorExtractor extractor{thumbnailParams()};
  const cv::Mat a = colourImage(128, 64, 6);
  EXPECT_EQ(cv::norm(extractor.compute(a), extractor.compute(a.clone()), cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(extractor.compute(a), extractor.compute(colourImage(128, 64, 7)), cv::NORM_L1), 0.0);
}

TEST(DescriptorExtractor, IsInvariantToBrightnessAndContrastChanges) {
  const DescriptorExtractor extractor{thumbnailParams()};
  const cv::Mat image = colourImage(128, 64, 8);
  cv::Mat changed;
  image.convertTo(changed, -1, 0.5, 40.0);  // Half the contrast, brighter.
  // Within a level or two of rounding everywhere.
  const double mean_difference =
      cv::norm(extractor.compute(image), extractor.compute(changed), cv::NORM_L1) / extractor.size();
  EXPECT_LT(mean_difference, 2.0);
}

}  // namespace
}  // namespace mrs_vpr
