#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <vector>

#include <opencv2/core.hpp>

#include "mrs_vpr/contrast_enhancement.hpp"
#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/difference_matrix.hpp"
#include "mrs_vpr/mrs/lazy_difference_matrix.hpp"
#include "mrs_vpr/mrs/temporal_pooling.hpp"

namespace mrs_vpr {
namespace {

DescriptorSequence sequenceFrom(const std::vector<std::vector<std::uint8_t>>& frames) {
  DescriptorSequence sequence(static_cast<int>(frames.front().size()));
  for (const auto& bytes : frames) {
    sequence.append(cv::Mat(1, static_cast<int>(bytes.size()), CV_8U, const_cast<std::uint8_t*>(bytes.data())));
  }
  return sequence;
}

/// `frames` pseudo-random descriptors of `size` bytes, seeded.
DescriptorSequence randomSequence(int frames, int size, int seed) {
  DescriptorSequence sequence(size);
  cv::RNG rng(static_cast<std::uint64_t>(seed));
  cv::Mat row(1, size, CV_8U);
  for (int f = 0; f < frames; ++f) {
    rng.fill(row, cv::RNG::UNIFORM, 60, 200);
    sequence.append(row);
  }
  return sequence;
}

TEST(PoolCell, AveragesTheFramesEndingAtTheEndAndRunsOfPixels) {
  const DescriptorSequence sequence = sequenceFrom({{0, 0, 0, 0}, {10, 20, 30, 40}, {30, 40, 50, 61}});
  std::vector<std::uint8_t> out(4);
  // Stride 2 ending at frame 2: frames 1 and 2.
  poolCell(sequence.view(), 2, 2, 1, out.data());
  EXPECT_EQ(out, (std::vector<std::uint8_t>{20, 30, 40, 51}));  // 50.5 rounds up.
  // Clipped at the start: stride 4 ending at frame 1 averages frames 0 and 1.
  poolCell(sequence.view(), 1, 4, 1, out.data());
  EXPECT_EQ(out, (std::vector<std::uint8_t>{5, 10, 15, 20}));
  // Pixel pooling 2 on frames 1 and 2: (10 + 20 + 30 + 40) / 4, (30 + 40 + 50 + 61) / 4.
  std::vector<std::uint8_t> pooled(2);
  poolCell(sequence.view(), 2, 2, 2, pooled.data());
  EXPECT_EQ(pooled, (std::vector<std::uint8_t>{25, 45}));
  // Stride 1 without pixel pooling is the frame itself.
  poolCell(sequence.view(), 2, 1, 1, out.data());
  EXPECT_EQ(out, (std::vector<std::uint8_t>{30, 40, 50, 61}));
}

TEST(PoolCell, RejectsPixelPoolingThatDoesNotDivideTheSize) {
  const DescriptorSequence sequence = sequenceFrom({{1, 2, 3, 4}});
  std::vector<std::uint8_t> out(4);
  EXPECT_THROW(poolCell(sequence.view(), 0, 1, 3, out.data()), std::invalid_argument);
}

TEST(PoolSequence, CellsEndAtFirstEndPlusMultiplesOfTheStride) {
  const DescriptorSequence sequence = randomSequence(20, 8, 1);
  const DescriptorSequence pooled = poolSequence(sequence.view(), 3, 4, 4, 2);  // Ends 3, 7, 11, 15.
  ASSERT_EQ(pooled.size(), 4);
  ASSERT_EQ(pooled.descriptorSize(), 4);
  std::vector<std::uint8_t> expected(4);
  for (int i = 0; i < 4; ++i) {
    poolCell(sequence.view(), 3 + 4 * i, 4, 2, expected.data());
    EXPECT_TRUE(std::equal(expected.begin(), expected.end(), pooled.descriptor(i))) << "cell " << i;
  }
}

TEST(PixelRunSums, PoolsTheSameCellsAsPoolSequence) {
  // Uneven uint8 values make rounding matter; strides and ends reach past both ends of the sequence.
  const DescriptorSequence sequence = randomSequence(37, 24, 7);
  for (const int pixel_pooling : {1, 2, 3, 4, 8}) {
    const PixelRunSums sums(sequence.view(), pixel_pooling);
    for (const int stride : {1, 2, 4, 8, 16}) {
      for (const int first_end : {0, 3, 5}) {
        // As many cells as hold a frame: with most strides the last one ends past the sequence.
        const int count = (36 + stride - 1 - first_end) / stride + 1;
        const DescriptorSequence expected = poolSequence(sequence.view(), first_end, stride, count, pixel_pooling);
        const DescriptorSequence pooled = sums.pool(first_end, stride, count);
        ASSERT_EQ(pooled.size(), count);
        ASSERT_EQ(pooled.descriptorSize(), 24 / pixel_pooling);
        for (int i = 0; i < count; ++i) {
          EXPECT_TRUE(
              std::equal(pooled.descriptor(i), pooled.descriptor(i) + 24 / pixel_pooling, expected.descriptor(i)))
              << "pixel pooling " << pixel_pooling << ", stride " << stride << ", first end " << first_end
              << ", cell " << i;
        }
      }
    }
  }
}

TEST(PixelRunSums, RejectsAPoolingThatDoesNotDivideTheDescriptor) {
  const DescriptorSequence sequence = randomSequence(3, 24, 8);
  EXPECT_THROW(PixelRunSums(sequence.view(), 5), std::invalid_argument);
}

TEST(PooledReference, CellsMatchPoolCellWithOrWithoutKeptCells) {
  DescriptorSequence plain = randomSequence(41, 16, 2);
  DescriptorSequence kept = randomSequence(41, 16, 2);
  kept.keepPooledCells(3, 4);
  PooledReference from_plain(plain.view(), 4, 4);
  PooledReference from_kept(kept.view(), 4, 4);
  EXPECT_EQ(from_plain.size(), 11);
  EXPECT_EQ(from_plain.cellSize(), 4);
  std::vector<std::uint8_t> expected(4);
  for (int j = 0; j < from_plain.size(); ++j) {
    poolCell(plain.view(), 4 * j, 4, 4, expected.data());
    EXPECT_TRUE(std::equal(expected.begin(), expected.end(), from_plain.cell(j))) << "cell " << j;
    EXPECT_TRUE(std::equal(expected.begin(), expected.end(), from_kept.cell(j))) << "cell " << j;
  }
  // The kept store is read in place.
  EXPECT_EQ(from_kept.cell(3), kept.view().pooledCells(4, 4).frame(3));
}

TEST(LazyDifferenceMatrix, EnhancedRowsEqualTheDenseEnhancedMatrix) {
  const DescriptorSequence reference = randomSequence(90, 32, 3);
  const DescriptorSequence query = randomSequence(6, 32, 4);
  const int window = 10;
  const cv::Mat dense = enhanceContrast(computeDifferenceMatrix(query.view(), reference.view()), window);
  LazyDifferenceMatrix lazy(query.view(), reference.view(), 1, 1, window);
  EXPECT_EQ(lazy.rows(), 6);
  EXPECT_EQ(lazy.columns(), 90);
  // Ranges at the edges (clipped windows), in the middle, and overlapping earlier requests.
  const std::vector<std::pair<int, int>> ranges{{0, 7}, {40, 52}, {83, 90}, {45, 60}, {0, 90}};
  for (int row = 0; row < lazy.rows(); ++row) {
    for (const auto& [begin, end] : ranges) {
      std::vector<float> out(static_cast<std::size_t>(end - begin));
      lazy.enhancedRow(row, begin, end, out.data());
      for (int c = begin; c < end; ++c) {
        EXPECT_NEAR(out[static_cast<std::size_t>(c - begin)], dense.at<float>(row, c), 1e-4F)
            << "row " << row << ", column " << c;
      }
    }
  }
  // Every raw cell was computed exactly once.
  EXPECT_EQ(lazy.comparisons(), 6 * 90);
}

TEST(LazyDifferenceMatrix, PooledColumnsAndRawRowsWithoutEnhancement) {
  const DescriptorSequence reference = randomSequence(64, 32, 5);
  const DescriptorSequence query = randomSequence(4, 8, 6);  // Already pooled: 32 / 4 bytes.
  const DescriptorSequence cells = poolSequence(reference.view(), 0, 2, 32, 4);
  const cv::Mat dense = computeDifferenceMatrix(query.view(), cells.view());
  LazyDifferenceMatrix lazy(query.view(), reference.view(), 2, 4, 0);
  EXPECT_EQ(lazy.columns(), 32);
  std::vector<float> out(5);
  lazy.enhancedRow(2, 10, 15, out.data());
  for (int c = 10; c < 15; ++c) EXPECT_FLOAT_EQ(out[static_cast<std::size_t>(c - 10)], dense.at<float>(2, c));
  EXPECT_EQ(lazy.comparisons(), 5);
  lazy.enhancedRow(2, 11, 14, out.data());  // Already known: no new comparison.
  EXPECT_EQ(lazy.comparisons(), 5);
}

TEST(DescriptorDifference, IsTheMeanAbsoluteDifferenceInStandardDeviations) {
  std::vector<std::uint8_t> a(64, 128);
  std::vector<std::uint8_t> b(64, 128);
  b[0] = 192;  // 64 levels = 2 std on one of 64 bytes.
  EXPECT_FLOAT_EQ(descriptorDifference(a.data(), b.data(), 64), 2.0F / 64.0F);
  EXPECT_FLOAT_EQ(descriptorDifference(a.data(), a.data(), 64), 0.0F);
  const DescriptorSequence q = randomSequence(2, 16, 7);
  const DescriptorSequence r = randomSequence(3, 8, 8);
  EXPECT_THROW(computeDifferenceMatrix(q.view(), r.view()), std::invalid_argument);
}

}  // namespace
}  // namespace mrs_vpr
