#pragma once

#include <string>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace mrs_vpr {
namespace node {
namespace testing {

/// A BGR image whose red rises to the right and whose blue rises downwards: grey made with red and
/// blue swapped, as a wrong Bayer pattern would give, differs from its true grey by ~16 levels on average.
inline cv::Mat redAcrossBlueDown(int width = 96, int height = 64) {
  cv::Mat image(height, width, CV_8UC3);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      image.at<cv::Vec3b>(y, x) = cv::Vec3b(static_cast<uchar>(255 * y / (height - 1)), 128,
                                            static_cast<uchar>(255 * x / (width - 1)));
    }
  }
  return image;
}

/// The raw frame a Bayer sensor with colour filters `pattern` ("rggb", "bggr", "gbrg", "grbg": the
/// top-left 2 x 2 block, row by row) records of `bgr`: one colour a pixel.
inline cv::Mat mosaicOf(const cv::Mat& bgr, const std::string& pattern) {
  cv::Mat mosaic(bgr.size(), CV_8UC1);
  const auto channel = [](char colour) { return colour == 'b' ? 0 : colour == 'g' ? 1 : 2; };
  for (int y = 0; y < bgr.rows; ++y) {
    for (int x = 0; x < bgr.cols; ++x) {
      const char colour = pattern[static_cast<std::size_t>(2 * (y % 2) + x % 2)];
      mosaic.at<uchar>(y, x) = bgr.at<cv::Vec3b>(y, x)[channel(colour)];
    }
  }
  return mosaic;
}

/// Mean absolute difference between two grey images of one depth, a border of 2 pixels left out
/// (demosaicing guesses there).
inline double interiorDifference(const cv::Mat& a, const cv::Mat& b) {
  const cv::Rect interior(2, 2, a.cols - 4, a.rows - 4);
  return cv::norm(a(interior), b(interior), cv::NORM_L1) / interior.area();
}

/// The grey of `bgr` as the front ends make it of a colour frame.
inline cv::Mat greyOf(const cv::Mat& bgr) {
  cv::Mat grey;
  cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
  return grey;
}

}  // namespace testing
}  // namespace node
}  // namespace mrs_vpr
