#pragma once

#include <cstddef>
#include <cstdint>

#include <opencv2/core.hpp>

#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/query_stop.hpp"

namespace mrs_vpr {

/// Mean absolute difference of two descriptors in patch standard deviations (SIMD sum of absolute
/// differences on the uint8 rows).
float descriptorDifference(const std::uint8_t* a, const std::uint8_t* b, int size);

/// out[i] = descriptorDifference(query, cells + i * pitch, size) for i in [0, count): one test frame
/// against consecutive reference cells, with the per-pair work vectorised and nothing else per pair.
void descriptorDifferences(const std::uint8_t* query, const std::uint8_t* cells, std::ptrdiff_t pitch, int count,
                           int size, float* out);

/// D(t, r) = descriptorDifference(query t, reference r): CV_32FC1, query.count x reference.count.
/// Rows are filled in parallel. Throws std::invalid_argument when descriptor sizes differ.
cv::Mat computeDifferenceMatrix(SequenceView query, SequenceView reference);

/// The same into `differences`, an existing CV_32FC1 matrix (or region of one) of query.count x
/// reference.count, so that columns from different sources can fill one matrix without copies. Throws
/// QueryStopped, the matrix part filled, when `stop` asks to stop (checked before each block of columns).
void computeDifferenceMatrix(SequenceView query, SequenceView reference, cv::Mat& differences,
                             const QueryStop* stop = nullptr);

}  // namespace mrs_vpr
