#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/objdetect.hpp>

#include "mrs_vpr/descriptor.hpp"
#include "mrs_vpr/front_end/hog_front_end.hpp"
#include "mrs_vpr/parameters.hpp"
#include "support/error_message.hpp"

namespace mrs_vpr {
namespace {

using testing_support::invalidArgumentMessage;

/// Deterministic textured grey image.
cv::Mat texture(int width, int height, int seed) {
  cv::Mat image(height, width, CV_8UC1);
  cv::RNG rng(static_cast<std::uint64_t>(seed));
  rng.fill(image, cv::RNG::UNIFORM, 0, 256);
  cv::GaussianBlur(image, image, cv::Size(9, 9), 3.0);
  cv::normalize(image, image, 0, 255, cv::NORM_MINMAX);
  return image;
}

/// The default HOG front end, which does not smooth the window.
DescriptorParams unblurred() { return DescriptorParams{}; }

TEST(HogFrontEnd, IsTheDefaultWithSevenByThreeBlocksOfFourCellsOfNineBins) {
  const DescriptorExtractor extractor{DescriptorParams{}};
  EXPECT_TRUE(extractor.params().isHog());
  EXPECT_EQ(extractor.size(), 7 * 3 * 4 * 9);
  const cv::Mat descriptor = extractor.compute(texture(640, 480, 1));
  EXPECT_EQ(descriptor.type(), CV_8UC1);
  EXPECT_EQ(descriptor.rows, 1);
  EXPECT_EQ(descriptor.cols, 756);
  EXPECT_TRUE(descriptor.isContinuous());
}

TEST(HogFrontEnd, BytesAreOpenCvsHistogramsOfTheWindowTimes510) {
  const DescriptorParams params = unblurred();
  const cv::Mat window = texture(128, 64, 2);  // Already the window's size: resizing keeps it.
  cv::HOGDescriptor hog(cv::Size(128, 64), cv::Size(32, 32), cv::Size(16, 16), cv::Size(16, 16), 9);
  std::vector<float> expected;
  hog.compute(window, expected);
  const cv::Mat descriptor = DescriptorExtractor(params).compute(window);
  ASSERT_EQ(descriptor.total(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const float scaled = std::min(255.0F, expected[i] * HogFrontEnd::kLevelsPerUnit);
    EXPECT_NEAR(descriptor.at<std::uint8_t>(0, static_cast<int>(i)), scaled, 0.5F + 1e-3F) << i;
  }
}

TEST(HogFrontEnd, OffsetFollowsOpenCvsLayoutOfBlocksAndCells) {
  // A vertical edge inside HOG cell (5, 2) only: its gradients are horizontal (bin 0 or 8 of
  // 0..180 degrees), and they appear in the four blocks that hold the cell, at that cell's place.
  cv::Mat image(64, 128, CV_8UC1, cv::Scalar(0));
  image(cv::Rect(5 * 16 + 8, 2 * 16, 8, 16)).setTo(255);
  const HogFrontEnd hog(unblurred());
  const cv::Mat descriptor = hog.describeGrey(image);
  for (int bx = 4; bx <= 5; ++bx) {
    for (int by = 1; by <= 2; ++by) {
      const std::uint8_t* cell = descriptor.ptr<std::uint8_t>() + hog.offset(bx, by, 5 - bx, 2 - by);
      EXPECT_GT(cell[0] + cell[8], 100) << "block " << bx << ", " << by;
      // Within its block, the edge's cell holds the strongest horizontal gradients.
      for (int cx = 0; cx < 2; ++cx) {
        for (int cy = 0; cy < 2; ++cy) {
          const std::uint8_t* other = descriptor.ptr<std::uint8_t>() + hog.offset(bx, by, cx, cy);
          EXPECT_LE(other[0] + other[8], cell[0] + cell[8]);
        }
      }
    }
  }
  // A block that does not hold the cell sees nothing.
  const std::uint8_t* far = descriptor.ptr<std::uint8_t>() + hog.offset(0, 0, 0, 0);
  for (int bin = 0; bin < 9; ++bin) EXPECT_EQ(far[bin], 0);
}

TEST(HogFrontEnd, BrightnessOffsetsAndBlurredCopiesGiveNearlyTheSameDescriptor) {
  const DescriptorExtractor extractor{DescriptorParams{}};
  const cv::Mat image = texture(320, 240, 3);
  cv::Mat brighter;
  image.convertTo(brighter, CV_8U, 1.0, 20.0);
  cv::Mat blurred;
  cv::GaussianBlur(image, blurred, cv::Size(), 1.0);
  const cv::Mat a = extractor.compute(image);
  const cv::Mat other = extractor.compute(texture(320, 240, 4));
  const double different = cv::norm(a, other, cv::NORM_L1);
  const double brighter_off = cv::norm(a, extractor.compute(brighter), cv::NORM_L1);
  EXPECT_LT(brighter_off, 0.05 * different) << brighter_off << " vs " << different;
  // A blur of one pixel (a slightly defocused or moving camera) changes far less than another place.
  const double blurred_off = cv::norm(a, extractor.compute(blurred), cv::NORM_L1);
  EXPECT_LT(blurred_off, 0.25 * different) << blurred_off << " vs " << different;
}

TEST(HogFrontEnd, BlurKeepsANoisyCopyNearerItsOriginal) {
  const cv::Mat image = texture(128, 64, 13);
  cv::Mat noise(image.size(), CV_16SC1);
  cv::RNG(14).fill(noise, cv::RNG::NORMAL, 0, 30);
  cv::Mat noisy;
  cv::add(image, noise, noisy, cv::noArray(), CV_8U);
  const auto relativeDistance = [&](double blur) {
    DescriptorParams params;
    params.hog_blur = blur;
    const DescriptorExtractor extractor(params);
    const cv::Mat original = extractor.compute(image);
    return cv::norm(original, extractor.compute(noisy), cv::NORM_L1) /
           cv::norm(original, extractor.compute(texture(128, 64, 15)), cv::NORM_L1);
  };
  EXPECT_LT(relativeDistance(2.0), 0.8 * relativeDistance(0.0));
}

TEST(HogFrontEnd, SixteenBitImageGivesTheDescriptorOfItsEightBitOriginal) {
  const DescriptorExtractor extractor{DescriptorParams{}};
  const cv::Mat image = texture(320, 240, 5);  // Spans 0..255.
  cv::Mat wide;
  image.convertTo(wide, CV_16U, 257.0);  // Spans 0..65535.
  const cv::Mat a = extractor.compute(image);
  const cv::Mat b = extractor.compute(wide);
  // Equal but for rounding: the 16-bit image is shrunk in 16 bits, the 8-bit one in 8.
  EXPECT_LE(cv::norm(a, b, cv::NORM_INF), 4.0);
  EXPECT_LT(cv::norm(a, b, cv::NORM_L1), 0.05 * cv::norm(a, extractor.compute(texture(320, 240, 16)), cv::NORM_L1));
}

TEST(HogFrontEnd, ColourOrderAndStridedImagesAreHonoured) {
  const DescriptorExtractor extractor{DescriptorParams{}};
  cv::Mat colour;
  cv::merge(std::vector<cv::Mat>{texture(200, 100, 6), texture(200, 100, 7), texture(200, 100, 8)}, colour);
  cv::Mat swapped;
  cv::cvtColor(colour, swapped, cv::COLOR_BGR2RGB);
  EXPECT_EQ(cv::norm(extractor.compute(colour), extractor.compute(swapped, ChannelOrder::kRgb), cv::NORM_INF), 0.0);
  const cv::Mat large = texture(400, 300, 9);
  const cv::Mat region = large(cv::Rect(50, 40, 200, 150));
  ASSERT_FALSE(region.isContinuous());
  EXPECT_EQ(cv::norm(extractor.compute(region), extractor.compute(region.clone()), cv::NORM_INF), 0.0);
}

TEST(HogFrontEnd, DescribingOneSizeThenAnotherGivesWhatAFreshExtractorGives) {
  // Buffers are kept per thread from frame to frame; a new size must not reuse stale ones.
  const DescriptorExtractor extractor{DescriptorParams{}};
  const cv::Mat small = texture(160, 120, 10);
  const cv::Mat large = texture(640, 480, 11);
  const cv::Mat first = extractor.compute(small);
  extractor.compute(large);
  EXPECT_EQ(cv::norm(first, extractor.compute(small), cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(DescriptorExtractor(DescriptorParams{}).compute(large), extractor.compute(large), cv::NORM_INF),
            0.0);
}

TEST(HogFrontEnd, InvalidWindowsAndCellsAreRefusedNamingTheParameter) {
  DescriptorParams not_dividing;
  not_dividing.hog_cell_size = 24;
  const std::string message = invalidArgumentMessage([&] { DescriptorExtractor{not_dividing}; });
  EXPECT_EQ(message.rfind("descriptor/hog/cell_size must be", 0), 0U) << message;
  EXPECT_NE(message.find("window 128 x 64"), std::string::npos) << message;
  DescriptorParams one_cell;
  one_cell.hog_window_height = 16;
  EXPECT_EQ(invalidArgumentMessage([&] { DescriptorExtractor{one_cell}; }).rfind("descriptor/hog/cell_size", 0), 0U);
  DescriptorParams too_many_bins;
  too_many_bins.hog_bins = 37;
  EXPECT_EQ(invalidArgumentMessage([&] { DescriptorExtractor{too_many_bins}; }).rfind("descriptor/hog/bins must be", 0),
            0U);
}

TEST(HogFrontEnd, PictureDrawsEdgesOnTheWindowsGridAndNothingForAFlatImage) {
  const HogFrontEnd hog{DescriptorParams{}};
  const cv::Mat textured = hog.picture(hog.describeGrey(texture(256, 128, 12)).ptr<std::uint8_t>());
  EXPECT_EQ(textured.size(), cv::Size(128, 64));
  EXPECT_EQ(textured.type(), CV_8UC1);
  EXPECT_GT(cv::countNonZero(textured), 500);
  const cv::Mat flat = hog.picture(hog.describeGrey(cv::Mat(64, 128, CV_8UC1, cv::Scalar(90))).ptr<std::uint8_t>());
  EXPECT_EQ(cv::countNonZero(flat), 0);
}

TEST(DescriptorParams, FrontEndsAreComparedOnTheFieldsTheirTypeUses) {
  DescriptorParams hog;
  DescriptorParams other_thumbnail = hog;
  other_thumbnail.image_width = 32;  // Not used by HOG.
  EXPECT_TRUE(hog.sameFrontEnd(other_thumbnail));
  DescriptorParams finer = hog;
  finer.hog_cell_size = 8;
  EXPECT_FALSE(hog.sameFrontEnd(finer));
  DescriptorParams thumbnail = hog;
  thumbnail.type = kThumbnailFrontEnd;
  EXPECT_FALSE(hog.sameFrontEnd(thumbnail));
  EXPECT_EQ(hog.describe(), "hog (128 x 64 window, cells of 16 px, 9 bins)");
  DescriptorParams blurred = hog;
  blurred.hog_blur = 1.5;
  EXPECT_EQ(blurred.describe(), "hog (128 x 64 window, cells of 16 px, 9 bins, blur 1.5 px)");
  EXPECT_FALSE(hog.sameFrontEnd(blurred));
  EXPECT_EQ(thumbnail.describe(), "thumbnail (64 x 32, patches of 8 px)");
  EXPECT_EQ(finer.descriptorSize(), 15 * 7 * 4 * 9);
}

}  // namespace
}  // namespace mrs_vpr
