#include "mrs_vpr/difference_matrix.hpp"

#include <stdexcept>
#include <string>

#include <opencv2/core/hal/hal.hpp>

#include "mrs_vpr/descriptor.hpp"

namespace mrs_vpr {

float descriptorDifference(const std::uint8_t* a, const std::uint8_t* b, int size) {
  // OpenCV's HAL sum of absolute differences is vectorised (SSE/AVX/NEON) for uint8. One
  // multiplication turns it into a mean in patch standard deviations.
  const float scale = 1.0F / (static_cast<float>(size) * DescriptorExtractor::kLevelsPerStd);
  return static_cast<float>(cv::hal::normL1_(a, b, size)) * scale;
}

cv::Mat computeDifferenceMatrix(SequenceView query, SequenceView reference) {
  cv::Mat differences(query.count, reference.count, CV_32F);
  computeDifferenceMatrix(query, reference, differences);
  return differences;
}

void computeDifferenceMatrix(SequenceView query, SequenceView reference, cv::Mat& differences) {
  if (query.descriptor_size != reference.descriptor_size) {
    throw std::invalid_argument("query descriptors have " + std::to_string(query.descriptor_size) +
                                " bytes but reference descriptors have " +
                                std::to_string(reference.descriptor_size));
  }
  CV_Assert(differences.type() == CV_32FC1 && differences.rows == query.count && differences.cols == reference.count);
  // Blocks of reference frames are swept for all query frames so that a block stays in cache.
  constexpr int kBlock = 64;
  const int blocks = (reference.count + kBlock - 1) / kBlock;
  cv::parallel_for_(cv::Range(0, blocks), [&](const cv::Range& range) {
    for (int block = range.start; block < range.end; ++block) {
      const int begin = block * kBlock;
      const int end = std::min(reference.count, begin + kBlock);
      for (int t = 0; t < query.count; ++t) {
        float* row = differences.ptr<float>(t);
        const std::uint8_t* q = query.frame(t);
        for (int r = begin; r < end; ++r) {
          row[r] = descriptorDifference(q, reference.frame(r), query.descriptor_size);
        }
      }
    }
  });
}

}  // namespace mrs_vpr
