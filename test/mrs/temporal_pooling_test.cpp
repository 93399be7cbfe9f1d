#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <tuple>
#include <vector>

#include <opencv2/core.hpp>

#include "mrs_vpr/contrast_enhancement.hpp"
#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/difference_matrix.hpp"
#include "mrs_vpr/mrs/lazy_difference_matrix.hpp"
#include "mrs_vpr/mrs/patch_frequencies.hpp"
#include "mrs_vpr/mrs/sampling_level.hpp"
#include "mrs_vpr/mrs/temporal_pooling.hpp"
#include "support/front_ends.hpp"

namespace mrs_vpr {
namespace {

using testing_support::thumbnailParams;

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

/// 32-byte descriptors as 8 x 4 images of 2 x 2 patches: 8 patches, 24-byte cells.
DescriptorParams smallGeometry() {
  DescriptorParams geometry = thumbnailParams();
  geometry.image_width = 8;
  geometry.image_height = 4;
  geometry.patch_size = 2;
  return geometry;
}

TEST(PooledReference, CellsMatchPatchFrequenciesWithOrWithoutKeptCells) {
  const PatchFrequencies frequencies(smallGeometry());
  DescriptorSequence plain = randomSequence(41, 32, 2);
  DescriptorSequence kept = randomSequence(41, 32, 2);
  kept.keepCoarseCells(3, smallGeometry());
  PooledReference from_plain(plain.view(), 4, frequencies);
  PooledReference from_kept(kept.view(), 4, frequencies);
  EXPECT_EQ(from_plain.size(), 11);
  EXPECT_EQ(from_plain.cellSize(), 24);
  std::vector<std::uint8_t> expected(24);
  for (int j = 0; j < from_plain.size(); ++j) {
    frequencies.cell(plain.view(), 4 * j, 4, expected.data());
    EXPECT_TRUE(std::equal(expected.begin(), expected.end(), from_plain.cell(j))) << "cell " << j;
    EXPECT_TRUE(std::equal(expected.begin(), expected.end(), from_kept.cell(j))) << "cell " << j;
  }
  // The kept store is read in place; at stride 1 the cells are the frames.
  EXPECT_EQ(from_kept.cell(3), kept.view().coarseCells(4, smallGeometry()).frame(3));
  PooledReference frames(plain.view(), 1, frequencies);
  EXPECT_EQ(frames.cellSize(), 32);
  EXPECT_EQ(frames.cell(5), plain.view().frame(5));
}

TEST(PooledReference, HoldsEveryCellOfItsSamplingLevelUpToThePartialLastOne) {
  // 42 frames at stride 4: the level's grid ends with cell 11, ending at frame 44 past the newest
  // (41), which pools frame 41 alone. The search asks for it like any other cell; a reference one
  // cell short let the contrast window read past its row.
  const PatchFrequencies frequencies(smallGeometry());
  const DescriptorSequence plain = randomSequence(42, 32, 9);
  DescriptorSequence kept = randomSequence(42, 32, 9);
  kept.keepCoarseCells(3, smallGeometry());
  const SamplingLevel level = SamplingLevel::make(4, SequenceRows{0, 19, 19}, 42, 0.8);
  ASSERT_EQ(level.grid_size, 12);
  PooledReference from_plain(plain.view(), 4, frequencies);
  PooledReference from_kept(kept.view(), 4, frequencies);
  ASSERT_EQ(from_plain.size(), level.grid_size);
  ASSERT_EQ(from_kept.size(), level.grid_size);
  std::vector<std::uint8_t> expected(24);
  frequencies.cell(plain.view(), 44, 4, expected.data());
  EXPECT_TRUE(std::equal(expected.begin(), expected.end(), from_plain.cell(11)));
  EXPECT_TRUE(std::equal(expected.begin(), expected.end(), from_kept.cell(11)));
}

TEST(LazyDifferenceMatrix, EnhancedRowsReachThePartialLastCellOfTheGrid) {
  const PatchFrequencies frequencies(smallGeometry());
  const DescriptorSequence reference = randomSequence(42, 32, 10);
  const DescriptorSequence query = frequencies.cells(randomSequence(12, 32, 11).view(), 3, 4, 3);
  const SamplingLevel level = SamplingLevel::make(4, SequenceRows{0, 11, 11}, 42, 0.8);
  const int window = 4;
  const cv::Mat dense = enhanceContrast(
      computeDifferenceMatrix(query.view(), frequencies.cells(reference.view(), 0, 4, level.grid_size).view()), window);
  LazyDifferenceMatrix lazy(query.view(), reference.view(), 4, frequencies, window);
  ASSERT_EQ(lazy.columns(), level.grid_size);
  std::vector<float> out(4);
  for (int row = 0; row < lazy.rows(); ++row) {
    lazy.enhancedRow(row, level.grid_size - 4, level.grid_size, out.data());
    for (int c = level.grid_size - 4; c < level.grid_size; ++c) {
      EXPECT_EQ(out[static_cast<std::size_t>(c - (level.grid_size - 4))], dense.at<float>(row, c))
          << "row " << row << ", column " << c;
    }
  }
}

TEST(LazyDifferenceMatrix, EnhancedRowsEqualTheDenseEnhancedMatrix) {
  const DescriptorSequence reference = randomSequence(90, 32, 3);
  const DescriptorSequence query = randomSequence(6, 32, 4);
  const int window = 10;
  const cv::Mat dense = enhanceContrast(computeDifferenceMatrix(query.view(), reference.view()), window);
  const PatchFrequencies frequencies(smallGeometry());
  LazyDifferenceMatrix lazy(query.view(), reference.view(), 1, frequencies, window);
  EXPECT_EQ(lazy.rows(), 6);
  EXPECT_EQ(lazy.columns(), 90);
  // Ranges at the edges (clipped windows), in the middle, and overlapping earlier requests.
  const std::vector<std::pair<int, int>> ranges{{0, 7}, {40, 52}, {83, 90}, {45, 60}, {0, 90}};
  for (int row = 0; row < lazy.rows(); ++row) {
    for (const auto& [begin, end] : ranges) {
      std::vector<float> out(static_cast<std::size_t>(end - begin));
      lazy.enhancedRow(row, begin, end, out.data());
      for (int c = begin; c < end; ++c) {
        EXPECT_EQ(out[static_cast<std::size_t>(c - begin)], dense.at<float>(row, c))  // To the bit.
            << "row " << row << ", column " << c;
      }
    }
  }
  // Every raw cell was computed exactly once.
  EXPECT_EQ(lazy.comparisons(), 6 * 90);
}

TEST(LazyDifferenceMatrix, AMatrixAfterAnotherOnTheSameThreadReusesItsRowsAndComputesEveryCellAnew) {
  // The first matrix leaves its rows' storage, wide and full of its own differences, to the next
  // one on this thread, which has more rows, fewer columns, and intervals that grow to either side;
  // the last request reads every cell again, after the moves.
  const std::vector<std::pair<int, int>> growing{{200, 204}, {150, 156}, {260, 270}, {100, 103}, {100, 270}};
  const int window = 6;
  const PatchFrequencies frequencies(smallGeometry());
  for (const auto& [frames, rows, seed] : {std::tuple{300, 5, 20}, std::tuple{280, 9, 22}, std::tuple{300, 3, 24}}) {
    const DescriptorSequence reference = randomSequence(frames, 32, seed);
    const DescriptorSequence query = randomSequence(rows, 32, seed + 1);
    const cv::Mat dense = enhanceContrast(computeDifferenceMatrix(query.view(), reference.view()), window);
    LazyDifferenceMatrix lazy(query.view(), reference.view(), 1, frequencies, window);
    for (int row = 0; row < rows; ++row) {
      for (const auto& [begin, end] : growing) {
        std::vector<float> out(static_cast<std::size_t>(end - begin));
        lazy.enhancedRow(row, begin, end, out.data());
        for (int c = begin; c < end; ++c) {
          EXPECT_EQ(out[static_cast<std::size_t>(c - begin)], dense.at<float>(row, c))
              << frames << " frames, row " << row << ", column " << c;
        }
      }
    }
    // Columns 97 .. 272 (the requests and half a window beyond) once each, and column 0, the
    // enhancement's origin.
    EXPECT_EQ(lazy.comparisons(), rows * 177LL);
  }
}

TEST(LazyDifferenceMatrix, PooledColumnsAndRawRowsWithoutEnhancement) {
  const PatchFrequencies frequencies(smallGeometry());
  const DescriptorSequence reference = randomSequence(64, 32, 5);
  const DescriptorSequence query = frequencies.cells(randomSequence(8, 32, 6).view(), 1, 2, 4);  // Test cells.
  const DescriptorSequence cells = frequencies.cells(reference.view(), 0, 2, 32);
  const cv::Mat dense = computeDifferenceMatrix(query.view(), cells.view());
  LazyDifferenceMatrix lazy(query.view(), reference.view(), 2, frequencies, 0);
  EXPECT_EQ(lazy.columns(), 33);  // The last cell ends at frame 64, past the newest (63).
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
