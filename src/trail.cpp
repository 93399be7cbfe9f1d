#include "mrs_vpr/trail.hpp"

#include <stdexcept>
#include <string>
#include <utility>

namespace mrs_vpr {

Trail::Trail(int descriptor_size, int keep) : keep_(keep), held_(descriptor_size) {
  if (keep < 1) throw std::invalid_argument("a trail keeps at least 1 keyframe, got " + std::to_string(keep));
}

void Trail::append(const cv::Mat& descriptor, Stamp stamp) {
  if (held_.size() >= 2 * keep_) {
    // The newest `keep_` moved to the front at once: each keyframe is copied about twice in all.
    const int from = held_.size() - keep_;
    DescriptorSequence newest = copy(dropped_ + from, size());
    held_ = std::move(newest);
    dropped_ += from;
  }
  held_.append(descriptor, stamp);
}

DescriptorSequence Trail::copy(std::int64_t begin, std::int64_t end) const {
  if (begin < dropped_ || end > size() || begin > end) {
    throw std::invalid_argument("keyframes " + std::to_string(begin) + " to " + std::to_string(end) +
                                " of the trail are not held (it holds " + std::to_string(oldest()) + " to " +
                                std::to_string(size()) + ")");
  }
  DescriptorSequence copied(held_.descriptorSize());
  copied.reserve(static_cast<int>(end - begin));
  for (auto i = static_cast<int>(begin - dropped_); i < static_cast<int>(end - dropped_); ++i) {
    copied.append(held_.descriptorRow(i), held_.stamp(i));
  }
  return copied;
}

}  // namespace mrs_vpr
