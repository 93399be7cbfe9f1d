#include "mrs_vpr/contrast_enhancement.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace mrs_vpr {
namespace {

float zScore(float centre, double sum, double sum_of_squares, int count) {
  if (count < 2) return 0.0F;
  const double mean = sum / count;
  const double variance = (sum_of_squares - sum * mean) / (count - 1);
  if (variance <= 1e-12) return 0.0F;
  return static_cast<float>((centre - mean) / std::sqrt(variance));
}

}  // namespace

float contrastShift(int window) {
  if (window <= 0) return 0.0F;
  const double samples = window + 1.0;
  return static_cast<float>((samples - 1.0) / std::sqrt(samples));
}

float enhanceCell(float centre, const float* values, int count, int window) {
  double sum = 0.0;
  double sum_of_squares = 0.0;
  for (int i = 0; i < count; ++i) {
    sum += values[i];
    sum_of_squares += static_cast<double>(values[i]) * values[i];
  }
  return zScore(centre, sum, sum_of_squares, count) + contrastShift(window);
}

cv::Mat enhanceContrast(const cv::Mat& differences, int window) {
  CV_Assert(differences.type() == CV_32FC1);
  if (window == 0) return differences.clone();
  const int half = window / 2;
  const int columns = differences.cols;
  const float shift = contrastShift(window);
  cv::Mat enhanced(differences.size(), CV_32F);
  cv::parallel_for_(cv::Range(0, differences.rows), [&](const cv::Range& rows) {
    // Prefix sums make every window O(1); doubles keep them exact enough for thousands of columns.
    std::vector<double> prefix(columns + 1);
    std::vector<double> prefix_of_squares(columns + 1);
    for (int row = rows.start; row < rows.end; ++row) {
      const float* in = differences.ptr<float>(row);
      float* out = enhanced.ptr<float>(row);
      for (int c = 0; c < columns; ++c) {
        prefix[c + 1] = prefix[c] + in[c];
        prefix_of_squares[c + 1] = prefix_of_squares[c] + static_cast<double>(in[c]) * in[c];
      }
      // Edges, where the window is clipped.
      const auto clipped = [&](int c) {
        const int begin = std::max(0, c - half);
        const int end = std::min(columns, c + half + 1);
        out[c] = zScore(in[c], prefix[end] - prefix[begin], prefix_of_squares[end] - prefix_of_squares[begin],
                        end - begin) +
                 shift;
      };
      const int interior_begin = std::min(columns, half);
      const int interior_end = std::max(interior_begin, columns - half);
      for (int c = 0; c < interior_begin; ++c) clipped(c);
      for (int c = interior_end; c < columns; ++c) clipped(c);
      // Interior: a full window of n samples; branch-free so that the loop vectorises.
      const double n = 2 * half + 1;
      for (int c = interior_begin; c < interior_end; ++c) {
        const double sum = prefix[c + half + 1] - prefix[c - half];
        const double mean = sum / n;
        const double variance = (prefix_of_squares[c + half + 1] - prefix_of_squares[c - half] - sum * mean) / (n - 1);
        const double z = variance > 1e-12 ? (in[c] - mean) / std::sqrt(std::max(variance, 1e-12)) : 0.0;
        out[c] = static_cast<float>(z) + shift;
      }
    }
  });
  return enhanced;
}

}  // namespace mrs_vpr
