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

/// sums[c] = values[c] + ... + values[c + n - 1] for c in [0, count - n], from the sums of 1, 2, 4,
/// ... values that n's binary digits select: O(log n) contiguous passes, each of which vectorises.
/// `scratch` holds 2 * count floats.
MRS_VPR_VECTOR_KERNEL
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

/**
 * The enhanced values of the cells whose whole window of n values lies in `values` (count of them):
 * out[i] for the cell values[i + n / 2]. Sums over every window come from sliding sums in O(log n)
 * contiguous, vectorised passes. The values are centred on the middle one, so that sum of squares
 * minus squared sum keeps its precision in single precision: a window's values then differ from the
 * centre by about the row's spread, not by their mean. `buffers` holds 6 * count floats.
 */
MRS_VPR_VECTOR_KERNEL
void enhanceInterior(const float* values, int count, int n, float shift, float* out, float* buffers) {
  float* __restrict y = buffers;
  float* __restrict y2 = y + count;
  float* __restrict s1 = y2 + count;  // s1[i]: the sum of the window of cell i + n / 2.
  float* __restrict s2 = s1 + count;
  float* scratch = s2 + count;  // 2 * count floats.
  const float pivot = values[count / 2];
  for (int c = 0; c < count; ++c) {
    y[c] = values[c] - pivot;
    y2[c] = y[c] * y[c];
  }
  slidingSums(y, count, n, s1, scratch);
  slidingSums(y2, count, n, s2, scratch);
  const int half = n / 2;
  const int outputs = count - n + 1;
  const float inverse_n = 1.0F / static_cast<float>(n);
  const float inverse_n1 = 1.0F / static_cast<float>(n - 1);
  const float* __restrict centre = y + half;
  for (int i = 0; i < outputs; ++i) {
    const float mean = s1[i] * inverse_n;
    const float variance = std::max(0.0F, (s2[i] - s1[i] * mean) * inverse_n1);
    // A constant window gives no contrast; a multiplication rather than a branch vectorises.
    const float deviation = (centre[i] - mean) * static_cast<float>(variance > kMinVariance);
    // No z-score over n samples lies below -shift; single precision could round past it.
    out[i] = std::max(0.0F, deviation / std::sqrt(std::max(variance, kMinVariance)) + shift);
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

void enhanceRowSpan(const float* raw, int columns, int begin, int end, int window, float* out) {
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
    const int first = interior_begin - half;
    const int count = interior_end - interior_begin + 2 * half;
    thread_local std::vector<float> buffers;  // Kept between rows and calls: no allocation per row.
    buffers.resize(6 * static_cast<std::size_t>(count));
    enhanceInterior(raw + (first - raw_begin), count, 2 * half + 1, contrastShift(window),
                    out + (interior_begin - begin), buffers.data());
  }
}

cv::Mat enhanceContrast(const cv::Mat& differences, int window) {
  CV_Assert(differences.type() == CV_32FC1);
  if (window == 0) return differences.clone();
  cv::Mat enhanced(differences.size(), CV_32F);
  cv::parallel_for_(cv::Range(0, differences.rows), [&](const cv::Range& rows) {
    for (int row = rows.start; row < rows.end; ++row) {
      enhanceRowSpan(differences.ptr<float>(row), differences.cols, 0, differences.cols, window, enhanced.ptr<float>(row));
    }
  });
  return enhanced;
}

}  // namespace mrs_vpr
