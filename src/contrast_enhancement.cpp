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

/// sums[c] = values[c] + ... + values[c + n - 1] for c in [0, count - n], from the sums of 1, 2, 4,
/// ... values that n's binary digits select: O(log n) contiguous passes, each of which vectorises.
/// `scratch` holds 2 * count floats.
void slidingSums(const float* values, int count, int n, float* __restrict sums, float* scratch) {
  const int outputs = count - n + 1;
  std::fill(sums, sums + outputs, 0.0F);
  const float* power = values;  // power[c]: the sum of `width` values from c, for c <= count - width.
  float* next = scratch;
  int width = 1;
  int offset = 0;
  for (;;) {
    if ((n & width) != 0) {
      const float* __restrict part = power + offset;
      for (int c = 0; c < outputs; ++c) sums[c] += part[c];
      offset += width;
    }
    if (2 * width > n) break;
    const int valid = count - 2 * width + 1;
    const float* __restrict low = power;
    const float* __restrict high = power + width;
    float* __restrict doubled = next;
    for (int c = 0; c < valid; ++c) doubled[c] = low[c] + high[c];
    power = next;
    next = next == scratch ? scratch + count : scratch;
    width *= 2;
  }
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
  return enhanceCellFromSums(centre, sum, sum_of_squares, count, window);
}

float enhanceCellFromSums(float centre, double sum, double sum_of_squares, int count, int window) {
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
    std::vector<float> centred(static_cast<std::size_t>(columns));
    std::vector<float> squares(static_cast<std::size_t>(columns));
    std::vector<float> sums(static_cast<std::size_t>(columns));
    std::vector<float> sums_of_squares(static_cast<std::size_t>(columns));
    std::vector<float> scratch(2 * static_cast<std::size_t>(columns));
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
      if (interior_begin >= interior_end) continue;
      // Interior: a full window of n samples. Sums over every window come from sliding sums in
      // O(log n) contiguous, vectorised passes. The values are centred on one of the row's first, so
      // that sum of squares minus squared sum keeps its precision in single precision: a window's
      // values then differ from the centre by about the row's spread, not by their mean. Any value
      // of the row will do as the centre; the middle one costs nothing.
      const int n = 2 * half + 1;
      const float pivot = in[columns / 2];
      float* __restrict y = centred.data();
      float* __restrict y2 = squares.data();
      for (int c = 0; c < columns; ++c) {
        y[c] = in[c] - pivot;
        y2[c] = y[c] * y[c];
      }
      slidingSums(y, columns, n, sums.data(), scratch.data());
      slidingSums(y2, columns, n, sums_of_squares.data(), scratch.data());
      const float* __restrict s1 = sums.data() - half;  // s1[c]: the window centred on column c.
      const float* __restrict s2 = sums_of_squares.data() - half;
      const float inverse_n = 1.0F / static_cast<float>(n);
      const float inverse_n1 = 1.0F / static_cast<float>(n - 1);
      for (int c = interior_begin; c < interior_end; ++c) {
        const float mean = s1[c] * inverse_n;
        const float variance = std::max(0.0F, (s2[c] - s1[c] * mean) * inverse_n1);
        // A constant window gives no contrast; a multiplication rather than a branch vectorises.
        const float deviation = (y[c] - mean) * static_cast<float>(variance > kMinVariance);
        // No z-score over n samples lies below -shift; single precision could round past it.
        out[c] = std::max(0.0F, deviation / std::sqrt(std::max(variance, kMinVariance)) + shift);
      }
    }
  });
  return enhanced;
}

}  // namespace mrs_vpr
