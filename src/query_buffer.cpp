#include "mrs_vpr/query_buffer.hpp"

#include <algorithm>

namespace mrs_vpr {

cv::Mat QueryBuffer::matrix(int rows, int cols) {
  const std::size_t cells = static_cast<std::size_t>(std::max(0, rows)) * static_cast<std::size_t>(std::max(0, cols));
  if (cells > storage_.capacity()) {
    // Room for a growing map: no reallocation for the next frames' columns.
    std::vector<float> larger;
    larger.reserve(std::max(cells, cells + cells / 8));
    storage_.swap(larger);
  }
  storage_.resize(cells);
  return cv::Mat(rows, cols, CV_32F, storage_.data());
}

void QueryBuffer::release() {
  if (capacityBytes() > kKeptQueryBufferBytes) std::vector<float>().swap(storage_);
}

}  // namespace mrs_vpr
