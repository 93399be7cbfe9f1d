#include "mrs_vpr/descriptor_sequence.hpp"

#include <stdexcept>
#include <string>

namespace mrs_vpr {

SequenceView SequenceView::slice(int begin, int end) const {
  if (begin < 0 || end > count || begin > end) {
    throw std::out_of_range("frames [" + std::to_string(begin) + ", " + std::to_string(end) +
                            ") are outside a sequence of " + std::to_string(count) + " frames");
  }
  return {frame(begin), end - begin, descriptor_size};
}

DescriptorSequence::DescriptorSequence(int descriptor_size) : descriptor_size_(descriptor_size) {
  if (descriptor_size <= 0) {
    throw std::invalid_argument("descriptor size must be positive, got " + std::to_string(descriptor_size));
  }
}

void DescriptorSequence::append(const cv::Mat& descriptor, double stamp) {
  if (descriptor.type() != CV_8UC1 || descriptor.total() != static_cast<std::size_t>(descriptor_size_) ||
      !descriptor.isContinuous()) {
    throw std::invalid_argument("descriptor must be a continuous CV_8UC1 row of " +
                                std::to_string(descriptor_size_) + " bytes, got " +
                                cv::typeToString(descriptor.type()) + " with " +
                                std::to_string(descriptor.total()) + " elements");
  }
  data_.insert(data_.end(), descriptor.data, descriptor.data + descriptor_size_);
  stamps_.push_back(stamp);
}

void DescriptorSequence::reserve(int frames) {
  data_.reserve(static_cast<std::size_t>(frames) * static_cast<std::size_t>(descriptor_size_));
  stamps_.reserve(static_cast<std::size_t>(frames));
}

void DescriptorSequence::clear() {
  data_.clear();
  stamps_.clear();
}

const std::uint8_t* DescriptorSequence::descriptor(int index) const {
  if (index < 0 || index >= size()) {
    throw std::out_of_range("frame " + std::to_string(index) + " is outside a sequence of " +
                            std::to_string(size()) + " frames");
  }
  return view().frame(index);
}

std::size_t DescriptorSequence::memoryBytes() const {
  return data_.capacity() + stamps_.capacity() * sizeof(double);
}

}  // namespace mrs_vpr
