#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/front_end/hog_front_end.hpp"
#include "mrs_vpr/mrs/hog_cells.hpp"
#include "mrs_vpr/mrs/patch_frequencies.hpp"
#include "support/front_ends.hpp"

namespace mrs_vpr {
namespace {

using testing_support::thumbnailParams;

/// HOG descriptors of deterministic textures.
DescriptorSequence describedTextures(int count, const DescriptorParams& params = DescriptorParams{}) {
  const HogFrontEnd hog{params};
  DescriptorSequence sequence(hog.size());
  cv::RNG rng(3);
  for (int i = 0; i < count; ++i) {
    cv::Mat image(96, 192, CV_8UC1);
    rng.fill(image, cv::RNG::UNIFORM, 0, 256);
    cv::GaussianBlur(image, image, cv::Size(7, 7), 2.0);
    sequence.append(hog.describeGrey(image));
  }
  return sequence;
}

TEST(HogCells, ThreeOrientationGroupsPerHogCell) {
  EXPECT_EQ(HogCells(DescriptorParams{}).cellSize(), 8 * 4 * 3);
  DescriptorParams eight_bins;
  eight_bins.hog_bins = 8;  // Groups of 3, 3 and 2 bins.
  EXPECT_EQ(HogCells(eight_bins).cellSize(), 8 * 4 * 3);
  DescriptorParams two_bins;
  two_bins.hog_bins = 2;
  EXPECT_EQ(HogCells(two_bins).cellSize(), 8 * 4 * 2);
}

/// Each byte of a cell of one frame of `params` is the mean of its HOG cell's bins over the blocks
/// that hold it.
void expectMeansOfBins(const DescriptorParams& params) {
  const HogFrontEnd hog(params);
  const HogCells cells(params);
  const DescriptorSequence frames = describedTextures(1, params);
  std::vector<std::uint8_t> cell(static_cast<std::size_t>(cells.cellSize()));
  cells.cell(frames.view(), 0, 1, cell.data());
  const std::uint8_t* descriptor = frames.descriptor(0);
  const int width = (params.hog_bins + 2) / 3;  // bins per group, the last group's fewer
  const int groups = (params.hog_bins + width - 1) / width;
  for (int cx = 0; cx < hog.cellsX(); ++cx) {
    for (int cy = 0; cy < hog.cellsY(); ++cy) {
      for (int group = 0; group < groups; ++group) {
        double sum = 0.0;
        int count = 0;
        for (int bx = std::max(0, cx - 1); bx <= std::min(hog.blocksX() - 1, cx); ++bx) {
          for (int by = std::max(0, cy - 1); by <= std::min(hog.blocksY() - 1, cy); ++by) {
            for (int bin = width * group; bin < std::min(params.hog_bins, width * group + width); ++bin) {
              sum += descriptor[hog.offset(bx, by, cx - bx, cy - by) + bin];
              ++count;
            }
          }
        }
        const int byte = (cx * hog.cellsY() + cy) * groups + group;
        EXPECT_NEAR(cell[static_cast<std::size_t>(byte)], sum / count, 0.5 + 1e-3) << cx << ", " << cy << ", " << group;
      }
    }
  }
}

TEST(HogCells, AByteIsTheMeanOfItsCellsBinsOverTheBlocksThatHoldIt) { expectMeansOfBins(DescriptorParams{}); }

// The default 9 bins are pooled by code of their own; other counts by the general loops.
TEST(HogCells, OtherBinCountsArePooledIntoTheirGroupsToo) {
  for (const int bins : {2, 8, 12}) {
    SCOPED_TRACE(bins);
    DescriptorParams params;
    params.hog_bins = bins;
    expectMeansOfBins(params);
  }
}

TEST(HogCells, CellsOfMoreThan256BytesAreTheMeansToo) {
  DescriptorParams large;
  large.hog_window_width = 256;
  large.hog_window_height = 128;  // 16 x 8 HOG cells: 384 cell bytes.
  ASSERT_EQ(HogCells(large).cellSize(), 16 * 8 * 3);
  expectMeansOfBins(large);
}

TEST(HogCells, ACellOfSeveralFramesIsTheMeanOfTheirCells) {
  const HogCells cells{DescriptorParams{}};
  const DescriptorSequence frames = describedTextures(4);
  const DescriptorSequence pooled = cells.cells(frames.view(), 3, 4, 1);
  const DescriptorSequence single = cells.cells(frames.view(), 0, 1, 4);
  for (int k = 0; k < cells.cellSize(); ++k) {
    double mean = 0.0;
    for (int f = 0; f < 4; ++f) mean += single.descriptor(f)[k] / 4.0;
    EXPECT_NEAR(pooled.descriptor(0)[k], mean, 1.0) << k;  // Each single cell was rounded on its own.
  }
}

TEST(CompactCells, EachFrontEndHasItsOwnAndRefusesTheOther) {
  EXPECT_NE(dynamic_cast<const HogCells*>(makeCompactCells(DescriptorParams{}).get()), nullptr);
  EXPECT_NE(dynamic_cast<const PatchFrequencies*>(makeCompactCells(thumbnailParams()).get()), nullptr);
  EXPECT_THROW(HogCells{thumbnailParams()}, std::invalid_argument);
  EXPECT_THROW(PatchFrequencies{DescriptorParams{}}, std::invalid_argument);
  DescriptorSequence kept(756);
  kept.keepCoarseCells(2, DescriptorParams{});
  EXPECT_EQ(kept.view().coarseCells(2, thumbnailParams()).count, 0);  // Another front end's cells are not offered.
}

}  // namespace
}  // namespace mrs_vpr
