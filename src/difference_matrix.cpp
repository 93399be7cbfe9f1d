#include "mrs_vpr/difference_matrix.hpp"

#include <stdexcept>
#include <string>

#include <opencv2/core/hal/hal.hpp>

#include "mrs_vpr/descriptor.hpp"
#include "simd/sum_of_absolute_differences.hpp"

namespace mrs_vpr {
namespace {

// Below this many bytes the call into OpenCV costs more than the sum itself (the coarse levels'
// compact cells): they are summed by the core's own kernel.
constexpr int kInlineSumBelow = 1024;

/// The factor that turns a sum of absolute differences of `size` bytes into a mean in patch
/// standard deviations.
float differenceScale(int size) { return 1.0F / (static_cast<float>(size) * DescriptorExtractor::kLevelsPerStd); }

}  // namespace

void descriptorDifferences(const std::uint8_t* query, const std::uint8_t* cells, std::ptrdiff_t pitch, int count,
                           int size, float* out) {
  const float scale = differenceScale(size);  // Once, not per pair: a division costs as much as a short sum.
  if (size < kInlineSumBelow) {
    simd::sumsOfAbsoluteDifferences(query, cells, pitch, count, size, scale, out);
    return;
  }
  for (int i = 0; i < count; ++i) out[i] = static_cast<float>(cv::hal::normL1_(query, cells + i * pitch, size)) * scale;
}

float descriptorDifference(const std::uint8_t* a, const std::uint8_t* b, int size) {
  float difference = 0.0F;
  descriptorDifferences(a, b, 0, 1, size, &difference);
  return difference;
}

cv::Mat computeDifferenceMatrix(SequenceView query, SequenceView reference) {
  cv::Mat differences(query.count, reference.count, CV_32F);
  computeDifferenceMatrix(query, reference, differences);
  return differences;
}

void computeDifferenceMatrix(SequenceView query, SequenceView reference, cv::Mat& differences,
                             const QueryStop* stop) {
  if (query.descriptor_size != reference.descriptor_size) {
    throw std::invalid_argument("query descriptors have " + std::to_string(query.descriptor_size) +
                                " bytes but reference descriptors have " +
                                std::to_string(reference.descriptor_size));
  }
  CV_Assert(differences.type() == CV_32FC1 && differences.rows == query.count && differences.cols == reference.count);
  // Blocks of reference frames are swept for all query frames so that a block stays in cache.
  constexpr int kBlock = 64;
  const int blocks = (reference.count + kBlock - 1) / kBlock;
  const int size = query.descriptor_size;
  cv::parallel_for_(cv::Range(0, blocks), [&](const cv::Range& range) {
    for (int block = range.start; block < range.end && !stopRequested(stop); ++block) {
      const int begin = block * kBlock;
      const int end = std::min(reference.count, begin + kBlock);
      for (int t = 0; t < query.count; ++t) {
        descriptorDifferences(query.frame(t), reference.frame(begin), reference.pitch(), end - begin, size,
                              differences.ptr<float>(t) + begin);
      }
    }
  });
  throwIfStopped(stop);
}

}  // namespace mrs_vpr
