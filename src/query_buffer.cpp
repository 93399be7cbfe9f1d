#include "mrs_vpr/query_buffer.hpp"

#include <algorithm>

namespace mrs_vpr {

cv::Mat QueryBuffer::matrix(int rows, int cols) {
  const std::size_t cells = static_cast<std::size_t>(std::max(0, rows)) * static_cast<std::size_t>(std::max(0, cols));
  if (cells > capacity_) {
    // Room for a growing map: no reallocation for the next frames' columns.
    const std::size_t capacity = std::max(cells, cells + cells / 8);
    storage_.reset();  // The old storage goes first: both may not fit.
    capacity_ = 0;
    storage_.reset(new float[capacity]);  // default-initialised: not zeroed
    capacity_ = capacity;
  }
  return cv::Mat(rows, cols, CV_32F, storage_.get());
}

void QueryBuffer::release() {
  if (capacityBytes() > kKeptQueryBufferBytes) {
    storage_.reset();
    capacity_ = 0;
  }
}

}  // namespace mrs_vpr
