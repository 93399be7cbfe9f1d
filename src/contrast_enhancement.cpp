#include "mrs_vpr/contrast_enhancement.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "simd/vector_kernel.hpp"

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

/// Sums of the values of every window, as the parts its width's binary digits select: parts[k][c]
/// sums `widths[k]` values from c + offsets[k], and the window of c is parts[0][c] + parts[1][c] +
/// ..., added in that order.
struct WindowParts {
  static constexpr int kMax = 32;
  const float* values[kMax];
  const float* squares[kMax];
  int count = 0;
};

/**
 * Sums of 1, 2, 4, ... consecutive values and squares (`y`, `y2`, count of each), doubling the
 * width in one vectorised pass for both, into `storage` (2 * count floats per doubling), and the
 * parts of a window of n values that n's binary digits select: O(log n) passes instead of n sums.
 */
MRS_VPR_VECTOR_KERNEL
WindowParts windowParts(const float* y, const float* y2, int count, int n, float* storage) {
  WindowParts parts;
  const float* power = y;  // power[c]: the sum of `width` values from c, for c <= count - width.
  const float* power2 = y2;
  int width = 1;
  int offset = 0;
  for (;;) {
    if ((n & width) != 0) {
      parts.values[parts.count] = power + offset;
      parts.squares[parts.count] = power2 + offset;
      ++parts.count;
      offset += width;
    }
    if (2 * width > n) break;
    const int valid = count - 2 * width + 1;
    float* __restrict doubled = storage;
    float* __restrict doubled2 = storage + count;
    const float* __restrict low = power;
    const float* __restrict low2 = power2;
    for (int c = 0; c < valid; ++c) {
      doubled[c] = low[c] + low[c + width];
      doubled2[c] = low2[c] + low2[c + width];
    }
    power = doubled;
    power2 = doubled2;
    storage += 2 * static_cast<std::ptrdiff_t>(count);
    width *= 2;
  }
  return parts;
}

/// Floats windowParts stores for n and count values.
std::size_t windowPartsStorage(int count, int n) {
  std::size_t doublings = 0;
  for (int width = 1; 2 * width <= n; width *= 2) ++doublings;
  return 2 * doublings * static_cast<std::size_t>(count);
}

/**
 * The enhanced values of the cells whose whole window of n values lies in `values` (count of them):
 * out[i] for the cell values[i + n / 2]. The values are taken relative to `pivot`, a value of the
 * same row, so that sum of squares minus squared sum keeps its precision in single precision: a
 * window's values then differ from it by about the row's spread, not by their mean. The window sums
 * are read straight from their parts (up to three; more are folded first), so the z-scores take one
 * more pass. A cell's parts and arithmetic depend on its window and the pivot alone, not on where
 * `values` starts. `buffers` holds 5 * count + windowPartsStorage(count, n) floats.
 */
MRS_VPR_VECTOR_KERNEL
void enhanceInterior(const float* values, int count, int n, float shift, float pivot, float* out, float* buffers) {
  float* y = buffers;
  float* y2 = y + count;
  float* folded = y2 + count;  // Parts folded together when there are more than three.
  float* folded2 = folded + count;
  float* zeros = folded2 + count;  // Stands for a missing part: x + 0 is x.
  for (int c = 0; c < count; ++c) {
    y[c] = values[c] - pivot;
    y2[c] = y[c] * y[c];
    zeros[c] = 0.0F;
  }
  WindowParts parts = windowParts(y, y2, count, n, zeros + count);
  const int outputs = count - n + 1;
  if (parts.count > 3) {
    // Left to right, as the window sum adds them: the first count - 2 into one part.
    std::copy(parts.values[0], parts.values[0] + outputs, folded);
    std::copy(parts.squares[0], parts.squares[0] + outputs, folded2);
    for (int k = 1; k < parts.count - 2; ++k) {
      const float* __restrict part = parts.values[k];
      const float* __restrict part2 = parts.squares[k];
      for (int i = 0; i < outputs; ++i) {
        folded[i] += part[i];
        folded2[i] += part2[i];
      }
    }
    parts = {{folded, parts.values[parts.count - 2], parts.values[parts.count - 1]},
             {folded2, parts.squares[parts.count - 2], parts.squares[parts.count - 1]},
             3};
  }
  for (int k = parts.count; k < 3; ++k) {
    parts.values[k] = zeros;
    parts.squares[k] = zeros;
  }
  const float* __restrict a = parts.values[0];
  const float* __restrict b = parts.values[1];
  const float* __restrict c = parts.values[2];
  const float* __restrict a2 = parts.squares[0];
  const float* __restrict b2 = parts.squares[1];
  const float* __restrict c2 = parts.squares[2];
  const float* __restrict centre = y + n / 2;
  float* __restrict enhanced = out;
  const float inverse_n = 1.0F / static_cast<float>(n);
  const float inverse_n1 = 1.0F / static_cast<float>(n - 1);
  for (int i = 0; i < outputs; ++i) {
    const float sum = (a[i] + b[i]) + c[i];
    const float sum_of_squares = (a2[i] + b2[i]) + c2[i];
    const float mean = sum * inverse_n;
    const float variance = std::max(0.0F, (sum_of_squares - sum * mean) * inverse_n1);
    // A constant window gives no contrast; a multiplication rather than a branch vectorises.
    const float deviation = (centre[i] - mean) * static_cast<float>(variance > kMinVariance);
    // No z-score over n samples lies below -shift; single precision could round past it.
    enhanced[i] = std::max(0.0F, deviation / std::sqrt(std::max(variance, kMinVariance)) + shift);
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
  return zScore(centre, sum, sum_of_squares, count) + contrastShift(window);
}

void enhanceRowSpan(const float* raw, int columns, int begin, int end, int window, float first_difference,
                    float* out) {
  if (window == 0) {
    std::copy(raw, raw + (end - begin), out);
    return;
  }
  const int half = window / 2;
  const int raw_begin = std::max(0, begin - half);
  // Columns whose window is clipped by an edge of the row.
  const int interior_begin = std::clamp(half, begin, end);
  const int interior_end = std::clamp(columns - half, interior_begin, end);
  const auto clipped = [&](int c) {
    const int low = std::max(0, c - half);
    const int high = std::min(columns, c + half + 1);
    out[c - begin] = enhanceCell(raw[c - raw_begin], raw + (low - raw_begin), high - low, window);
  };
  for (int c = begin; c < interior_begin; ++c) clipped(c);
  for (int c = interior_end; c < end; ++c) clipped(c);
  if (interior_begin < interior_end) {
    // The interior's windows cover raw columns [interior_begin - half, interior_end + half).
    const int window_begin = interior_begin - half;
    const int count = interior_end - interior_begin + 2 * half;
    thread_local std::vector<float> buffers;  // Kept between rows and calls: no allocation per row.
    buffers.resize(5 * static_cast<std::size_t>(count) + windowPartsStorage(count, 2 * half + 1));
    enhanceInterior(raw + (window_begin - raw_begin), count, 2 * half + 1, contrastShift(window),
                    first_difference, out + (interior_begin - begin), buffers.data());
  }
}

namespace {

/// Every row of `differences` enhanced into the same row of `enhanced`, which may be `differences`
/// itself; rows left once `stop` asks to stop.
void enhanceRows(const cv::Mat& differences, int window, cv::Mat& enhanced, const QueryStop* stop) {
  const bool in_place = differences.data == enhanced.data;
  cv::parallel_for_(cv::Range(0, differences.rows), [&](const cv::Range& rows) {
    // A row's windows read raw differences on both sides of each cell: in place, from a copy.
    std::vector<float> copy(in_place ? static_cast<std::size_t>(differences.cols) : 0);
    for (int row = rows.start; row < rows.end && !stopRequested(stop); ++row) {
      const float* raw = differences.ptr<float>(row);
      if (in_place) {
        std::copy(raw, raw + differences.cols, copy.begin());
        raw = copy.data();
      }
      const float first_difference = differences.cols > 0 ? raw[0] : 0.0F;
      enhanceRowSpan(raw, differences.cols, 0, differences.cols, window, first_difference,
                     enhanced.ptr<float>(row));
    }
  });
}

}  // namespace

cv::Mat enhanceContrast(const cv::Mat& differences, int window) {
  cv::Mat enhanced(differences.size(), CV_32F);
  enhanceContrast(differences, window, enhanced);
  return enhanced;
}

void enhanceContrast(const cv::Mat& differences, int window, cv::Mat& enhanced) {
  CV_Assert(differences.type() == CV_32FC1 && enhanced.type() == CV_32FC1 && enhanced.size() == differences.size());
  if (window == 0) {
    differences.copyTo(enhanced);
    return;
  }
  enhanceRows(differences, window, enhanced, nullptr);
}

void enhanceContrastInPlace(cv::Mat& matrix, int window, const QueryStop* stop) {
  CV_Assert(matrix.type() == CV_32FC1);
  if (window == 0) return;
  enhanceRows(matrix, window, matrix, stop);
  throwIfStopped(stop);
}

}  // namespace mrs_vpr
