#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/mrs/patch_frequencies.hpp"
#include "support/front_ends.hpp"

namespace mrs_vpr {
namespace {

using testing_support::thumbnailParams;

constexpr double kPi = 3.14159265358979323846;

/// The first DCT cosine of an 8-pixel patch row (orthonormal), at pixel x.
double wave(int x) { return std::sqrt(2.0 / 8.0) * std::cos(kPi * (2 * x + 1) / 16.0); }

/// A 64 x 32 descriptor whose every 8 x 8 patch is 128 + amplitude * wave(x) * [vertical ? wave(y) : 1].
cv::Mat waveDescriptor(double amplitude, bool vertical) {
  cv::Mat descriptor(1, 64 * 32, CV_8U);
  for (int y = 0; y < 32; ++y) {
    for (int x = 0; x < 64; ++x) {
      const double value = 128.0 + amplitude * (vertical ? wave(y % 8) : wave(x % 8));
      descriptor.at<std::uint8_t>(0, y * 64 + x) = cv::saturate_cast<std::uint8_t>(value);
    }
  }
  return descriptor;
}

std::vector<std::uint8_t> cellOf(const PatchFrequencies& frequencies, const std::vector<cv::Mat>& frames, int end,
                                 int stride) {
  DescriptorSequence sequence(frequencies.descriptorSize());
  for (const cv::Mat& frame : frames) sequence.append(frame);
  std::vector<std::uint8_t> cell(static_cast<std::size_t>(frequencies.cellSize()));
  frequencies.cell(sequence.view(), end, stride, cell.data());
  return cell;
}

TEST(PatchFrequencies, ThreeBytesPerPatch) {
  const PatchFrequencies frequencies{thumbnailParams()};
  EXPECT_EQ(frequencies.descriptorSize(), 2048);
  EXPECT_EQ(frequencies.cellSize(), 32 * 3);  // 8 x 4 patches of 8 x 8 pixels.
  DescriptorParams small = thumbnailParams();
  small.image_width = 8;
  small.image_height = 4;
  small.patch_size = 2;
  EXPECT_EQ(PatchFrequencies(small).cellSize(), 8 * 3);
  DescriptorParams invalid = small;
  invalid.patch_size = 3;
  EXPECT_THROW(PatchFrequencies{invalid}, std::invalid_argument);
}

TEST(PatchFrequencies, EachBasisPatternLandsInItsOwnByte) {
  const PatchFrequencies frequencies{thumbnailParams()};
  // A horizontal cosine of amplitude 60 along every patch row: coefficient 60 * sqrt(8) in the
  // horizontal slot, stored as 128 + coefficient / 2 (a normalised patch's bound, 256, maps to 128).
  const std::vector<std::uint8_t> horizontal = cellOf(frequencies, {waveDescriptor(60.0, false)}, 0, 1);
  const double expected = 128.0 + 60.0 * std::sqrt(8.0) / 2.0;
  for (int patch = 0; patch < 32; ++patch) {
    EXPECT_NEAR(horizontal[3 * patch], expected, 1.0) << "patch " << patch;
    EXPECT_NEAR(horizontal[3 * patch + 1], 128, 1) << "patch " << patch;
    EXPECT_NEAR(horizontal[3 * patch + 2], 128, 1) << "patch " << patch;
  }
  const std::vector<std::uint8_t> vertical = cellOf(frequencies, {waveDescriptor(60.0, true)}, 0, 1);
  for (int patch = 0; patch < 32; ++patch) {
    EXPECT_NEAR(vertical[3 * patch], 128, 1) << "patch " << patch;
    EXPECT_NEAR(vertical[3 * patch + 1], expected, 1.0) << "patch " << patch;
    EXPECT_NEAR(vertical[3 * patch + 2], 128, 1) << "patch " << patch;
  }
  // The opposite pattern (a mirrored patch) gives the opposite coefficient.
  const std::vector<std::uint8_t> mirrored = cellOf(frequencies, {waveDescriptor(-60.0, false)}, 0, 1);
  EXPECT_NEAR(mirrored[0], 256.0 - expected, 1.0);
}

TEST(PatchFrequencies, BrightnessOffsetsAreInvisibleAndExtremesSaturateWithoutWrapping) {
  const PatchFrequencies frequencies{thumbnailParams()};
  for (const int level : {0, 128, 200, 255}) {
    const std::vector<std::uint8_t> cell =
        cellOf(frequencies, {cv::Mat(1, 2048, CV_8U, cv::Scalar(level))}, 0, 1);
    for (std::uint8_t byte : cell) EXPECT_EQ(byte, 128) << "constant level " << level;
  }
  // The strongest horizontal pattern a byte can hold (0 or 255 by the sign of the cosine).
  const std::vector<std::uint8_t> extreme = cellOf(frequencies, {waveDescriptor(1000.0, false)}, 0, 1);
  EXPECT_GE(extreme[0], 240);
  const std::vector<std::uint8_t> opposite = cellOf(frequencies, {waveDescriptor(-1000.0, false)}, 0, 1);
  EXPECT_LE(opposite[0], 15);
}

TEST(PatchFrequencies, ACellIsTheTransformOfTheMeanOfItsFrames) {
  const PatchFrequencies frequencies{thumbnailParams()};
  const cv::Mat weak = waveDescriptor(20.0, false);
  const cv::Mat strong = waveDescriptor(100.0, false);
  // Stride 2 ending at frame 1 averages frames 0 and 1: the cell of amplitude 60, within rounding.
  const std::vector<std::uint8_t> pooled = cellOf(frequencies, {weak, strong}, 1, 2);
  const std::vector<std::uint8_t> middle = cellOf(frequencies, {waveDescriptor(60.0, false)}, 0, 1);
  for (std::size_t i = 0; i < pooled.size(); ++i) EXPECT_NEAR(pooled[i], middle[i], 1) << "byte " << i;
  // Clipped at the start: stride 4 ending at frame 0 is frame 0 alone.
  EXPECT_EQ(cellOf(frequencies, {weak, strong}, 0, 4), cellOf(frequencies, {weak}, 0, 1));
  // A cell may end past the frames that exist: it pools those that do.
  EXPECT_EQ(cellOf(frequencies, {weak, strong}, 2, 2), cellOf(frequencies, {strong}, 0, 1));
}

TEST(PatchFrequencies, CellsOfASequenceEndEveryStride) {
  const PatchFrequencies frequencies{thumbnailParams()};
  DescriptorSequence sequence(2048);
  cv::RNG rng(5);
  cv::Mat frame(1, 2048, CV_8U);
  for (int f = 0; f < 20; ++f) {
    rng.fill(frame, cv::RNG::UNIFORM, 40, 220);
    sequence.append(frame);
  }
  const DescriptorSequence cells = frequencies.cells(sequence.view(), 3, 4, 5);  // Ends 3, 7, 11, 15, 19.
  ASSERT_EQ(cells.size(), 5);
  ASSERT_EQ(cells.descriptorSize(), 96);
  std::vector<std::uint8_t> expected(96);
  for (int i = 0; i < 5; ++i) {
    frequencies.cell(sequence.view(), 3 + 4 * i, 4, expected.data());
    EXPECT_TRUE(std::equal(expected.begin(), expected.end(), cells.descriptor(i))) << "cell " << i;
  }
}

TEST(PatchFrequencies, DescriptorsOfAnotherSizeAreRefusedNamingBothSizes) {
  const PatchFrequencies frequencies{thumbnailParams()};
  DescriptorSequence small(64);
  small.append(cv::Mat(1, 64, CV_8U, cv::Scalar(1)));
  try {
    frequencies.cells(small.view(), 0, 2, 1);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("thumbnail (64 x 32, patches of 8 px) front end, 2048 bytes, got 64"), std::string::npos)
        << message;
  }
}

}  // namespace
}  // namespace mrs_vpr
