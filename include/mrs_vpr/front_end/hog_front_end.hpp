#pragma once

#include <opencv2/objdetect.hpp>

#include "mrs_vpr/front_end/front_end.hpp"

namespace mrs_vpr {

/**
 * Histograms of oriented gradients, computed by OpenCV's cv::HOGDescriptor over one window: the grey
 * image resized to the window (area interpolation), cells of `hog_cell_size` px, `hog_bins`
 * orientation bins over 0..180 degrees, blocks of 2 x 2 cells one cell apart, each block normalised
 * by L2-Hys (OpenCV's defaults otherwise). A 128 x 64 window with cells of 16 px gives 7 x 3 blocks of
 * 36 values: 756 bytes.
 *
 * Gradients, and blocks normalised on their own, keep the structure of a scene where its brightness
 * changes, which is what day against night asks of a descriptor (doc/front_ends.md).
 *
 * Values are quantised to one byte with a fixed scale, kLevelsPerUnit: L2-Hys leaves a block's values
 * in [0, 1] and on real frames all but 0.02% of them below 0.5, which maps to 255. The scale needs no
 * storing and the sum of absolute differences of the bytes is the L1 distance of the histograms.
 *
 * Layout (OpenCV's): block (bx, by) at offset (bx * blocksY() + by) * 4 * bins, its cell (cx, cy) at
 * (cx * 2 + cy) * bins within it.
 */
class HogFrontEnd : public FrontEnd {
 public:
  /// Quantisation steps per unit of a normalised histogram value: 0.5 is 255.
  static constexpr float kLevelsPerUnit = 510.0F;

  /// Uses the HOG fields of `params` (hog_window_width, hog_window_height, hog_cell_size, hog_bins,
  /// hog_blur).
  explicit HogFrontEnd(const DescriptorParams& params);

  cv::Mat describeGrey(const cv::Mat& grey) const override;
  int size() const override { return size_; }
  /// Each cell's histogram (the mean over the blocks that hold it) drawn as lines along the edges
  /// its gradients cross, brighter for stronger bins, on the window's grid.
  cv::Mat picture(const std::uint8_t* descriptor) const override;

  int cellsX() const { return params_.hog_window_width / params_.hog_cell_size; }
  int cellsY() const { return params_.hog_window_height / params_.hog_cell_size; }
  int blocksX() const { return cellsX() - 1; }
  int blocksY() const { return cellsY() - 1; }
  int bins() const { return params_.hog_bins; }
  /// Offset of cell (cx, cy) of block (bx, by) in a descriptor.
  int offset(int bx, int by, int cx, int cy) const { return ((bx * blocksY() + by) * 4 + cx * 2 + cy) * bins(); }

 private:
  DescriptorParams params_;
  cv::HOGDescriptor hog_;
  int size_ = 0;
};

}  // namespace mrs_vpr
