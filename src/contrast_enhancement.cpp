#include "mrs_vpr/contrast_enhancement.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace mrs_vpr {
namespace {

// Below this variance a window counts as constant and its cells get no contrast.
constexpr float kMinVariance = 1e-12F;

float zScore(float centre, double sum, double sum_of_squares, int count) {
  if (count < 2) return 0.0F;
  const double mean = sum / count;
  const double variance = (sum_of_squares - sum * mean) / (count - 1);
  if (variance <= kMinVariance) return 0.0F;
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
    std::vector<float> means(static_cast<std::size_t>(columns));
    std::vector<float> squares(static_cast<std::size_t>(columns));
    for (int row = rows.start; row < rows.end; ++row) {
      const float* in = differences.ptr<float>(row);
      float* out = enhanced.ptr<float>(row);
      // Edges, where the window is clipped.
      const int interior_begin = std::min(columns, half);
      const int interior_end = std::max(interior_begin, columns - half);
      const auto clipped = [&](int c) {
        const int begin = std::max(0, c - half);
        const int end = std::min(columns, c + half + 1);
        out[c] = enhanceCell(in[c], in + begin, end - begin, window);
      };
      for (int c = 0; c < interior_begin; ++c) clipped(c);
      for (int c = interior_end; c < columns; ++c) clipped(c);
      // Interior: a full window of n samples. Each pass below runs over contiguous columns and
      // vectorises; the two-pass variance (mean first) stays exact in single precision. Two
      // offsets per pass halve the loads and stores of the running sums.
      const int n = 2 * half + 1;
      float* __restrict mean = means.data();
      float* __restrict square = squares.data();
      std::fill(mean + interior_begin, mean + interior_end, 0.0F);
      std::fill(square + interior_begin, square + interior_end, 0.0F);
      int d = -half;
      for (; d + 1 <= half; d += 2) {
        for (int c = interior_begin; c < interior_end; ++c) mean[c] += in[c + d] + in[c + d + 1];
      }
      for (; d <= half; ++d) {
        for (int c = interior_begin; c < interior_end; ++c) mean[c] += in[c + d];
      }
      for (int c = interior_begin; c < interior_end; ++c) mean[c] /= static_cast<float>(n);
      for (d = -half; d + 1 <= half; d += 2) {
        for (int c = interior_begin; c < interior_end; ++c) {
          const float first = in[c + d] - mean[c];
          const float second = in[c + d + 1] - mean[c];
          square[c] += first * first + second * second;
        }
      }
      for (; d <= half; ++d) {
        for (int c = interior_begin; c < interior_end; ++c) {
          const float deviation = in[c + d] - mean[c];
          square[c] += deviation * deviation;
        }
      }
      for (int c = interior_begin; c < interior_end; ++c) {
        const float variance = square[c] / static_cast<float>(n - 1);
        // A constant window gives no contrast; a multiplication rather than a branch vectorises.
        const float deviation = (in[c] - mean[c]) * static_cast<float>(variance > kMinVariance);
        out[c] = deviation / std::sqrt(std::max(variance, kMinVariance)) + shift;
      }
    }
  });
  return enhanced;
}

}  // namespace mrs_vpr
