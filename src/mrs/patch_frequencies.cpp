#include "mrs_vpr/mrs/patch_frequencies.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "mrs_vpr/front_end/thumbnail_front_end.hpp"
#include "simd/vector_kernel.hpp"

namespace mrs_vpr {
namespace {

/// The three frequencies of every patch of one descriptor's pixel sums. Each is separable: the
/// horizontal one is the cosine-weighted sum over x of a patch's column sums, the vertical one the
/// plain sum over x of its cosine-weighted column sums, the mixed one the cosine-weighted sum of
/// the latter. So a band of patches (`side` image rows) is read once into two column accumulators
/// the width of the image, in contiguous loops that vectorise, and only those are reduced per patch.
/// `accumulators` holds 2 * width floats.
MRS_VPR_VECTOR_KERNEL
void transformPatches(const std::uint16_t* sums, int width, int height, int side, const float* wave, float scale,
                      std::uint8_t* cell, float* accumulators) {
  const float mean_weight = 1.0F / std::sqrt(static_cast<float>(side));  // The DCT's constant basis.
  float* __restrict columns = accumulators;              // Sum over the band's rows y of pixel (x, y).
  float* __restrict waved_columns = columns + width;     // The same weighted by wave(y).
  for (int top = 0; top < height; top += side) {
    std::fill(columns, columns + 2 * width, 0.0F);
    for (int y = 0; y < side; ++y) {
      const std::uint16_t* __restrict row = sums + static_cast<std::ptrdiff_t>(top + y) * width;
      const float weight = wave[y];
      for (int x = 0; x < width; ++x) {
        const auto value = static_cast<float>(row[x]);
        columns[x] += value;
        waved_columns[x] += weight * value;
      }
    }
    for (int left = 0; left < width; left += side) {
      float horizontal = 0.0F;
      float vertical = 0.0F;
      float both = 0.0F;
      for (int x = 0; x < side; ++x) {
        horizontal += wave[x] * columns[left + x];
        vertical += waved_columns[left + x];
        both += wave[x] * waved_columns[left + x];
      }
      // The constant offset of the uint8 descriptor (128) falls out: every basis used sums to 0.
      const float coefficients[PatchFrequencies::kPerPatch] = {horizontal * mean_weight, vertical * mean_weight, both};
      for (float coefficient : coefficients) {
        const float byte = std::clamp(128.0F + coefficient * scale, 0.0F, 255.0F);
        *cell++ = static_cast<std::uint8_t>(byte + 0.5F);
      }
    }
  }
}

}  // namespace

PatchFrequencies::PatchFrequencies(const DescriptorParams& geometry) : CompactCells(geometry) {
  if (geometry.isHog()) {
    throw std::invalid_argument("patch frequencies are the compact cells of thumbnails, not of " + geometry.describe());
  }
  const int side = geometry.patch_size;
  for (int x = 0; x < side; ++x) {
    wave_.push_back(static_cast<float>(std::sqrt(2.0 / side) * std::cos(M_PI * (2 * x + 1) / (2.0 * side))));
  }
}

int PatchFrequencies::cellSize() const {
  const int side = geometry().patch_size;
  return (geometry().image_width / side) * (geometry().image_height / side) * kPerPatch;
}

void PatchFrequencies::project(const std::uint16_t* sums, int frames, std::uint8_t* cell) const {
  // A normalised patch of side P has a norm of kLevelsPerStd * P levels, which bounds each of its
  // orthonormal coefficients: +-that bound maps to +-128, so a byte saturates only at the extreme.
  const int side = geometry().patch_size;
  const float scale =
      128.0F / (ThumbnailFrontEnd::kLevelsPerStd * static_cast<float>(side) * static_cast<float>(frames));
  thread_local std::vector<float> accumulators;
  accumulators.resize(2 * static_cast<std::size_t>(geometry().image_width));
  transformPatches(sums, geometry().image_width, geometry().image_height, side, wave_.data(), scale, cell,
                   accumulators.data());
}

}  // namespace mrs_vpr
