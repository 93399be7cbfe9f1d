#include "mrs_vpr/descriptor_sequence.hpp"

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include "mrs_vpr/mrs/compact_cells.hpp"

namespace mrs_vpr {

SequenceView SequenceView::slice(int begin, int end) const {
  if (begin < 0 || end > count || begin > end) {
    throw std::out_of_range("frames [" + std::to_string(begin) + ", " + std::to_string(end) +
                            ") are outside a sequence of " + std::to_string(count) + " frames");
  }
  SequenceView sliced{frame(begin), end - begin, descriptor_size, step};
  if (begin == 0) sliced.coarse = coarse;
  return sliced;
}

SequenceView SequenceView::coarseCells(int stride, const DescriptorParams& geometry) const {
  if (coarse == nullptr || step != 1 || count == 0) return {};
  if (!coarse->kind->geometry().sameFrontEnd(geometry)) return {};
  if (stride == 1) return {coarse->frames.data(), count, coarse->kind->cellSize(), 1};
  for (std::size_t level = 0; level < coarse->levels.size(); ++level) {
    if (stride == (2 << level)) {
      return {coarse->levels[level].data(), (count - 1) / stride + 1, coarse->kind->cellSize(), 1};
    }
  }
  return {};
}

SequenceView SequenceView::subsample(int first, int stride) const {
  if (first < 0 || stride < 1 || (count > 0 && first >= count)) {
    throw std::out_of_range("cannot subsample a sequence of " + std::to_string(count) + " frames from frame " +
                            std::to_string(first) + " with stride " + std::to_string(stride));
  }
  return {frame(first), count == 0 ? 0 : (count - first - 1) / stride + 1, descriptor_size, step * stride};
}

DescriptorSequence::DescriptorSequence(int descriptor_size) : descriptor_size_(descriptor_size) {
  if (descriptor_size <= 0) {
    throw std::invalid_argument("descriptor size must be positive, got " + std::to_string(descriptor_size));
  }
}

void requireDescriptorBytes(const cv::Mat& descriptor, int bytes, const std::string& what) {
  if (descriptor.type() != CV_8UC1 || descriptor.total() != static_cast<std::size_t>(bytes) ||
      !descriptor.isContinuous()) {
    throw std::invalid_argument(what + " must be " + std::to_string(bytes) + " continuous bytes of CV_8UC1, got " +
                                std::to_string(descriptor.total()) + " of type " + cv::typeToString(descriptor.type()) +
                                (descriptor.isContinuous() ? "" : ", not continuous"));
  }
}

void DescriptorSequence::append(const cv::Mat& descriptor, Stamp stamp) {
  requireDescriptorBytes(descriptor, descriptor_size_);
  // A failed allocation part-way through leaves every array as it was, not one frame longer than another.
  const int frames = size();
  try {
    data_.insert(data_.end(), descriptor.data, descriptor.data + descriptor_size_);
    stamps_.push_back(stamp);
    appendCoarseCells(size() - 1);
  } catch (...) {
    trimTo(frames);
    throw;
  }
}

void DescriptorSequence::trimTo(int frames) {
  const auto count = static_cast<std::size_t>(frames);
  data_.resize(count * static_cast<std::size_t>(descriptor_size_));
  stamps_.resize(count);
  if (coarse_.levels.empty()) return;
  const auto cell_size = static_cast<std::size_t>(coarse_.kind->cellSize());
  coarse_.frames.resize(count * cell_size);
  for (std::size_t level = 0; level < coarse_.levels.size(); ++level) {
    // Cells end at frames 0, stride, 2 * stride, ...
    const std::size_t stride = std::size_t{2} << level;
    const std::size_t cells = count == 0 ? 0 : (count - 1) / stride + 1;
    coarse_.levels[level].resize(cells * cell_size);
  }
}

void DescriptorSequence::appendCoarseCells(int last) {
  if (coarse_.levels.empty()) return;
  const auto cell_size = static_cast<std::size_t>(coarse_.kind->cellSize());
  coarse_.frames.resize(coarse_.frames.size() + cell_size);
  coarse_.kind->cell(view(), last, 1, coarse_.frames.data() + coarse_.frames.size() - cell_size);
  for (std::size_t level = 0; level < coarse_.levels.size(); ++level) {
    const int stride = 2 << level;
    if (last % stride != 0) continue;
    std::vector<std::uint8_t>& cells = coarse_.levels[level];
    cells.resize(cells.size() + cell_size);
    coarse_.kind->cell(view(), last, stride, cells.data() + cells.size() - cell_size);
  }
}

void DescriptorSequence::keepCoarseCells(int levels, const DescriptorParams& geometry) {
  auto kind = makeCompactCells(geometry);
  if (kind->descriptorSize() != descriptor_size_) {
    throw std::invalid_argument("coarse cells of the " + geometry.describe() +
                                " front end cannot be kept for descriptors of " + std::to_string(descriptor_size_) +
                                " bytes");
  }
  coarse_.kind = std::move(kind);
  coarse_.levels.assign(static_cast<std::size_t>(std::max(0, levels)), {});
  coarse_.frames.clear();
  for (int frame = 0; frame < size(); ++frame) appendCoarseCells(frame);
}

SequenceView DescriptorSequence::view() const {
  SequenceView whole{data_.data(), size(), descriptor_size_, 1};
  if (!coarse_.levels.empty()) whole.coarse = &coarse_;
  return whole;
}

void DescriptorSequence::reserve(int frames) {
  data_.reserve(static_cast<std::size_t>(frames) * static_cast<std::size_t>(descriptor_size_));
  stamps_.reserve(static_cast<std::size_t>(frames));
  if (!coarse_.levels.empty()) {
    coarse_.frames.reserve(static_cast<std::size_t>(frames) * static_cast<std::size_t>(coarse_.kind->cellSize()));
  }
  for (std::size_t level = 0; level < coarse_.levels.size(); ++level) {
    const std::size_t cells = static_cast<std::size_t>(frames) / (std::size_t{2} << level) + 1;
    coarse_.levels[level].reserve(cells * static_cast<std::size_t>(coarse_.kind->cellSize()));
  }
}

void DescriptorSequence::clear() {
  data_.clear();
  stamps_.clear();
  for (std::vector<std::uint8_t>& cells : coarse_.levels) cells.clear();
  coarse_.frames.clear();
}

cv::Mat DescriptorSequence::descriptorRow(int index) const {
  return cv::Mat(1, descriptor_size_, CV_8UC1, const_cast<std::uint8_t*>(descriptor(index)));
}

const std::uint8_t* DescriptorSequence::descriptor(int index) const {
  if (index < 0 || index >= size()) {
    throw std::out_of_range("frame " + std::to_string(index) + " is outside a sequence of " +
                            std::to_string(size()) + " frames");
  }
  return view().frame(index);
}

std::size_t DescriptorSequence::memoryBytes() const {
  std::size_t bytes = data_.capacity() + stamps_.capacity() * sizeof(Stamp);
  for (const std::vector<std::uint8_t>& cells : coarse_.levels) bytes += cells.capacity();
  bytes += coarse_.frames.capacity();
  return bytes;
}

}  // namespace mrs_vpr
