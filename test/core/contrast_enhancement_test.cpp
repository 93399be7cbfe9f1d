#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

#include "mrs_vpr/contrast_enhancement.hpp"
#include "mrs_vpr/front_end/thumbnail_front_end.hpp"

namespace mrs_vpr {
namespace {

constexpr float kTolerance = 1e-5F;

cv::Mat rowOf(const std::vector<float>& values) {
  return cv::Mat(1, static_cast<int>(values.size()), CV_32F, const_cast<float*>(values.data())).clone();
}

TEST(NormalisePatches, TwoByTwoPatchesGetZeroMeanUnitPopulationStd) {
  // Two 2 x 2 patches side by side: {1, 2; 3, 4} (mean 2.5, population std sqrt(1.25)) and a constant one.
  cv::Mat image = (cv::Mat_<float>(2, 4) << 1, 2, 7, 7, 3, 4, 7, 7);
  normalisePatches(image, 2);
  const float std_dev = std::sqrt(1.25F);
  EXPECT_NEAR(image.at<float>(0, 0), (1.0F - 2.5F) / std_dev, kTolerance);
  EXPECT_NEAR(image.at<float>(0, 1), (2.0F - 2.5F) / std_dev, kTolerance);
  EXPECT_NEAR(image.at<float>(1, 0), (3.0F - 2.5F) / std_dev, kTolerance);
  EXPECT_NEAR(image.at<float>(1, 1), (4.0F - 2.5F) / std_dev, kTolerance);
  // A constant patch becomes all zeros.
  EXPECT_EQ(image.at<float>(0, 2), 0.0F);
  EXPECT_EQ(image.at<float>(0, 3), 0.0F);
  EXPECT_EQ(image.at<float>(1, 2), 0.0F);
  EXPECT_EQ(image.at<float>(1, 3), 0.0F);
}

TEST(NormalisePatches, EveryPatchOfALargerImageIsStandardised) {
  cv::Mat image(8, 16, CV_32F);
  cv::RNG rng(3);
  rng.fill(image, cv::RNG::UNIFORM, 0.0, 255.0);
  normalisePatches(image, 4);
  for (int y = 0; y < 8; y += 4) {
    for (int x = 0; x < 16; x += 4) {
      cv::Scalar mean;
      cv::Scalar std_dev;
      cv::meanStdDev(image(cv::Rect(x, y, 4, 4)), mean, std_dev);
      EXPECT_NEAR(mean[0], 0.0, 1e-5) << "patch at " << x << ", " << y;
      EXPECT_NEAR(std_dev[0], 1.0, 1e-5) << "patch at " << x << ", " << y;
    }
  }
}

TEST(ContrastShift, IsTheBoundOnAZScoreOverWindowPlusOneSamples) {
  EXPECT_FLOAT_EQ(contrastShift(2), 2.0F / std::sqrt(3.0F));
  EXPECT_FLOAT_EQ(contrastShift(10), 10.0F / std::sqrt(11.0F));
  EXPECT_EQ(contrastShift(0), 0.0F);
}

TEST(EnhanceContrast, OneRowWithWindowTwoMatchesHandComputation) {
  // Window 2: cell c uses columns [c - 1, c + 1] clipped to the row; std with n - 1.
  const cv::Mat row = rowOf({1, 2, 3, 4, 10});
  const cv::Mat enhanced = enhanceContrast(row, 2);
  ASSERT_EQ(enhanced.type(), CV_32FC1);
  ASSERT_EQ(enhanced.size(), row.size());
  const float shift = 2.0F / std::sqrt(3.0F);
  // Column 0: {1, 2}, mean 1.5, std sqrt(0.5).
  EXPECT_NEAR(enhanced.at<float>(0, 0), -0.5F / std::sqrt(0.5F) + shift, kTolerance);
  // Columns 1 and 2: {1, 2, 3} and {2, 3, 4}, the centre is the mean.
  EXPECT_NEAR(enhanced.at<float>(0, 1), shift, kTolerance);
  EXPECT_NEAR(enhanced.at<float>(0, 2), shift, kTolerance);
  // Column 3: {3, 4, 10}, mean 17/3, variance 43/3.
  EXPECT_NEAR(enhanced.at<float>(0, 3), (4.0F - 17.0F / 3.0F) / std::sqrt(43.0F / 3.0F) + shift, kTolerance);
  // Column 4: {4, 10}, mean 7, std sqrt(18).
  EXPECT_NEAR(enhanced.at<float>(0, 4), 3.0F / std::sqrt(18.0F) + shift, kTolerance);
}

TEST(EnhanceContrast, ConstantRowsBecomeTheShiftOnly) {
  cv::Mat constant(3, 20, CV_32F, cv::Scalar(4.25F));
  const cv::Mat enhanced = enhanceContrast(constant, 10);
  for (int r = 0; r < enhanced.rows; ++r) {
    for (int c = 0; c < enhanced.cols; ++c) {
      EXPECT_FLOAT_EQ(enhanced.at<float>(r, c), contrastShift(10)) << r << ", " << c;
    }
  }
}

TEST(EnhanceContrast, RowsAreEnhancedIndependently) {
  const cv::Mat a = rowOf({5, 1, 4, 2, 8, 3, 9});
  const cv::Mat b = rowOf({0, 0, 1, 0, 0, 6, 2});
  cv::Mat both;
  cv::vconcat(a, b, both);
  const cv::Mat enhanced = enhanceContrast(both, 4);
  EXPECT_EQ(cv::norm(enhanced.row(0), enhanceContrast(a, 4), cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(enhanced.row(1), enhanceContrast(b, 4), cv::NORM_INF), 0.0);
}

TEST(EnhanceContrast, InPlaceGivesTheSameMatrixToTheBit) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> difference(0.0F, 3.0F);
  cv::Mat raw(37, 301, CV_32F);
  for (int r = 0; r < raw.rows; ++r) {
    for (int c = 0; c < raw.cols; ++c) raw.at<float>(r, c) = difference(random);
  }
  raw.row(5).setTo(1.0F);  // a constant row: no contrast
  for (const int window : {0, 1, 10, 300, 1000}) {
    cv::Mat in_place = raw.clone();
    enhanceContrastInPlace(in_place, window);
    EXPECT_EQ(cv::norm(in_place, enhanceContrast(raw, window), cv::NORM_INF), 0.0) << "window " << window;
  }
}

TEST(EnhanceContrast, WindowZeroReturnsAnIndependentCopy) {
  const cv::Mat row = rowOf({3, 1, 2});
  cv::Mat copy = enhanceContrast(row, 0);
  EXPECT_EQ(cv::norm(copy, row, cv::NORM_INF), 0.0);
  copy.at<float>(0, 0) = 100.0F;
  EXPECT_EQ(row.at<float>(0, 0), 3.0F);
}

TEST(EnhanceContrast, ShiftedValuesAreNeverNegative) {
  cv::Mat differences(16, 200, CV_32F);
  cv::RNG rng(11);
  rng.fill(differences, cv::RNG::UNIFORM, 0.0, 3.0);
  // A few isolated deep minima: the most negative z-scores a window can produce.
  for (int r = 0; r < differences.rows; ++r) differences.at<float>(r, (r * 13) % 200) = -50.0F;
  for (int window : {2, 3, 10, 31}) {
    double min_value = 0.0;
    cv::minMaxLoc(enhanceContrast(differences, window), &min_value);
    EXPECT_GE(min_value, -1e-5) << "window " << window;
  }
}

TEST(EnhanceRowSpan, PiecesOfARowAreTheWholeRowsCellsToTheBit) {
  // Differences around 1 with a spread of a tenth, as between real frames, where single precision
  // rounds differently whenever the window sums are taken relative to another value.
  std::vector<float> values(3000);
  std::mt19937 rng(9);
  std::normal_distribution<float> difference(1.0F, 0.1F);
  for (float& v : values) v = difference(rng);
  const int columns = static_cast<int>(values.size());
  for (int window : {4, 10, 31}) {
    const cv::Mat whole = enhanceContrast(rowOf(values), window);
    const int half = window / 2;
    // Pieces as a growing map, a lazy search and the kept rows cut a row: uneven, and at both edges.
    const std::vector<std::pair<int, int>> pieces{{0, 7}, {7, 1000}, {1000, 1001}, {1777, 2990}, {2990, 3000}};
    for (const auto& [begin, end] : pieces) {
      const int raw_begin = std::max(0, begin - half);
      std::vector<float> out(static_cast<std::size_t>(end - begin));
      enhanceRowSpan(values.data() + raw_begin, columns, begin, end, window, values[0], out.data());
      for (int c = begin; c < end; ++c) {
        ASSERT_EQ(out[static_cast<std::size_t>(c - begin)], whole.at<float>(0, c))
            << "window " << window << ", column " << c;
      }
    }
  }
}

TEST(EnhanceCell, AgreesWithEnhanceContrastOnEveryCell) {
  std::vector<float> values(30);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> uniform(0.0F, 2.0F);
  for (float& v : values) v = uniform(rng);
  const int window = 6;
  const cv::Mat enhanced = enhanceContrast(rowOf(values), window);
  const int columns = static_cast<int>(values.size());
  for (int c = 0; c < columns; ++c) {
    const int low = std::max(0, c - window / 2);
    const int high = std::min(columns, c + window / 2 + 1);
    EXPECT_NEAR(enhanceCell(values[static_cast<std::size_t>(c)], values.data() + low, high - low, window),
                enhanced.at<float>(0, c), 1e-4F)
        << "column " << c;
  }
}

TEST(EnhanceCell, HandComputedCellAndDegenerateWindows) {
  const float window_values[] = {2.0F, 4.0F, 9.0F};  // Mean 5, std (n - 1) sqrt(13).
  EXPECT_NEAR(enhanceCell(4.0F, window_values, 3, 2), -1.0F / std::sqrt(13.0F) + contrastShift(2), kTolerance);
  // One sample or no spread: z = 0, the shift remains.
  EXPECT_FLOAT_EQ(enhanceCell(2.0F, window_values, 1, 2), contrastShift(2));
  const float flat[] = {1.5F, 1.5F, 1.5F, 1.5F};
  EXPECT_FLOAT_EQ(enhanceCell(1.5F, flat, 4, 4), contrastShift(4));
}

}  // namespace
}  // namespace mrs_vpr
