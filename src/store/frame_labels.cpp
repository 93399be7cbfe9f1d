#include "mrs_vpr/store/frame_labels.hpp"

#include <algorithm>

namespace mrs_vpr {

void FrameLabels::prepareFor(const std::string& frame_id) {
  if (sequences_.size() == sequences_.capacity()) reserve(std::max<std::size_t>(16, 2 * sequences_.capacity()));
  const auto [found, added] = index_of_.try_emplace(frame_id, static_cast<std::uint32_t>(names_.size()));
  if (!added) return;
  try {
    names_.push_back(frame_id);
  } catch (...) {
    index_of_.erase(found);
    throw;
  }
}

void FrameLabels::append(const std::string& frame_id, std::int64_t sequence) {
  // The last frame's id first: a camera's frames all have the same one.
  if (name_of_.empty() || names_[name_of_.back()] != frame_id) prepareFor(frame_id);
  const std::uint32_t name =
      !name_of_.empty() && names_[name_of_.back()] == frame_id ? name_of_.back() : index_of_.at(frame_id);
  name_of_.push_back(name);
  sequences_.push_back(sequence);
}

void FrameLabels::clear() { *this = FrameLabels(); }

void FrameLabels::reserve(std::size_t frames) {
  name_of_.reserve(frames);
  sequences_.reserve(frames);
}

const std::string& FrameLabels::frameId(int index) const { return names_[name_of_.at(static_cast<std::size_t>(index))]; }

std::int64_t FrameLabels::sequence(int index) const { return sequences_.at(static_cast<std::size_t>(index)); }

std::size_t FrameLabels::memoryBytes() const {
  std::size_t bytes = name_of_.capacity() * sizeof(std::uint32_t) + sequences_.capacity() * sizeof(std::int64_t);
  for (const std::string& name : names_) bytes += 2 * (sizeof(std::string) + name.capacity());  // and its key
  return bytes;
}

bool FrameLabels::holds(int index, const std::string& frame_id, std::int64_t sequence) const {
  return index >= 0 && index < size() && sequence == sequences_[static_cast<std::size_t>(index)] &&
         frame_id == frameId(index);
}

}  // namespace mrs_vpr
