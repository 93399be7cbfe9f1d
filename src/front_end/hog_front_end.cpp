#include "mrs_vpr/front_end/hog_front_end.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include <opencv2/imgproc.hpp>

namespace mrs_vpr {

HogFrontEnd::HogFrontEnd(const DescriptorParams& params)
    : params_(params),
      hog_(cv::Size(params.hog_window_width, params.hog_window_height),
           cv::Size(2 * params.hog_cell_size, 2 * params.hog_cell_size),
           cv::Size(params.hog_cell_size, params.hog_cell_size), cv::Size(params.hog_cell_size, params.hog_cell_size),
           params.hog_bins) {
  size_ = static_cast<int>(hog_.getDescriptorSize());
  CV_Assert(size_ == params.descriptorSize());
}

namespace {

/// `image` resized to `size` by area interpolation. OpenCV's area interpolation is fast only for
/// whole-number factors: 640 x 480 to 128 x 64 (5 and 7.5) took 0.3 ms, three times as long as the
/// HOG itself. So the image is first shrunk by the largest whole factor that both its sides share and
/// that keeps it at least `size`, then by the rest (128 x 96, then 128 x 64: 0.1 ms in all), which
/// rounds once more on the way.
void shrink(const cv::Mat& image, cv::Size size, cv::Mat& between, cv::Mat& out) {
  const int factor = std::min(image.cols / size.width, image.rows / size.height);
  if (factor >= 2 && image.cols % factor == 0 && image.rows % factor == 0) {
    cv::resize(image, between, cv::Size(image.cols / factor, image.rows / factor), 0.0, 0.0, cv::INTER_AREA);
    cv::resize(between, out, size, 0.0, 0.0, cv::INTER_AREA);
  } else {
    cv::resize(image, out, size, 0.0, 0.0, cv::INTER_AREA);
  }
}

}  // namespace

cv::Mat HogFrontEnd::describeGrey(const cv::Mat& grey) const {
  // Kept per thread from frame to frame: a camera sends frames of one size.
  thread_local cv::Mat between;
  thread_local cv::Mat window;
  thread_local cv::Mat smoothed;
  thread_local cv::Mat window8;
  thread_local std::vector<float> values;
  // Resized in the image's own depth: converting a whole 640 x 480 frame to floats first cost more than
  // describing it.
  shrink(grey, cv::Size(params_.hog_window_width, params_.hog_window_height), between, window);
  const cv::Mat* source = &window;
  if (params_.hog_blur > 0.0) {
    window.convertTo(smoothed, CV_32F);
    cv::GaussianBlur(smoothed, smoothed, cv::Size(), params_.hog_blur);
    source = &smoothed;
  }
  // OpenCV's HOG takes 8-bit images: a 16-bit one is scaled so that the image's brightest pixel is 255 (a
  // 12-bit camera fills the bytes as an 8-bit one would). An
  // 8-bit one keeps its grey levels: OpenCV's block normalisation adds a constant to each block's norm,
  // which keeps faint gradients (sky, a wall) faint, and stretching the window's contrast would undo
  // that (on the real frames of doc/front_ends.md it cost up to 11 points of top-1).
  double gain = 1.0;
  if (grey.depth() == CV_16U) {
    double brightest = 0.0;
    cv::minMaxLoc(grey, nullptr, &brightest);
    gain = brightest > 0.0 ? 255.0 / brightest : 0.0;
  }
  if (source->type() == CV_8UC1) {
    hog_.compute(*source, values);
  } else {
    source->convertTo(window8, CV_8U, gain);
    hog_.compute(window8, values);
  }
  cv::Mat descriptor;
  cv::Mat(1, size_, CV_32FC1, values.data()).convertTo(descriptor, CV_8U, kLevelsPerUnit);
  return descriptor;
}

cv::Mat HogFrontEnd::picture(const std::uint8_t* descriptor) const {
  const int side = params_.hog_cell_size;
  cv::Mat canvas(cellsY() * side, cellsX() * side, CV_8UC1, cv::Scalar(0));
  std::vector<float> histogram(static_cast<std::size_t>(bins()));
  for (int cx = 0; cx < cellsX(); ++cx) {
    for (int cy = 0; cy < cellsY(); ++cy) {
      std::fill(histogram.begin(), histogram.end(), 0.0F);
      int blocks = 0;
      for (int bx = std::max(0, cx - 1); bx <= std::min(blocksX() - 1, cx); ++bx) {
        for (int by = std::max(0, cy - 1); by <= std::min(blocksY() - 1, cy); ++by) {
          const std::uint8_t* cell = descriptor + offset(bx, by, cx - bx, cy - by);
          for (int b = 0; b < bins(); ++b) histogram[static_cast<std::size_t>(b)] += cell[b];
          ++blocks;
        }
      }
      // Weakest bins first, so that the strongest edges are drawn on top.
      std::vector<int> order(static_cast<std::size_t>(bins()));
      std::iota(order.begin(), order.end(), 0);
      std::sort(order.begin(), order.end(), [&](int a, int b) {
        return histogram[static_cast<std::size_t>(a)] < histogram[static_cast<std::size_t>(b)];
      });
      const cv::Point2f centre((cx + 0.5F) * side, (cy + 0.5F) * side);
      for (int b : order) {
        // A bin counts gradients of its orientation; the edge they cross runs at right angles to it.
        const double edge = (b + 0.5) * M_PI / bins() + M_PI / 2.0;
        const cv::Point2f half(static_cast<float>(std::cos(edge) * side / 2.0),
                               static_cast<float>(std::sin(edge) * side / 2.0));
        const double level = std::min(255.0, 2.0 * histogram[static_cast<std::size_t>(b)] / blocks);
        cv::line(canvas, centre - half, centre + half, cv::Scalar(level), 1, cv::LINE_AA);
      }
    }
  }
  return canvas;
}

}  // namespace mrs_vpr
