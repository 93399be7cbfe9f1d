#include "mrs_vpr/store/frame_labels.hpp"

#include <algorithm>

namespace mrs_vpr {

void FrameLabels::prepareFor(const std::string& frame_id) {
  if (sequences_.size() == sequences_.capacity() || name_of_.size() == name_of_.capacity()) {
    reserve(std::max<std::size_t>(16, 2 * sequences_.size()));
  }
  prepared_a_new_name_ = false;
  const auto [found, added] = index_of_.try_emplace(frame_id, static_cast<std::uint32_t>(names_.size()));
  if (!added) return;
  try {
    names_.push_back(frame_id);
  } catch (...) {
    index_of_.erase(found);
    throw;
  }
  name_bytes_ += names_.back().capacity() + found->first.capacity();
  prepared_a_new_name_ = true;
}

void FrameLabels::cancelPrepared() {
  if (!prepared_a_new_name_) return;
  prepared_a_new_name_ = false;
  const auto found = index_of_.find(names_.back());
  name_bytes_ -= names_.back().capacity() + found->first.capacity();
  index_of_.erase(found);
  names_.pop_back();
}

void FrameLabels::append(const std::string& frame_id, std::int64_t sequence) {
  prepareFor(frame_id);  // Nothing to do when the frame was prepared for already.
  name_of_.push_back(index_of_.at(frame_id));
  sequences_.push_back(sequence);
  prepared_a_new_name_ = false;
}

void FrameLabels::clear() { *this = FrameLabels(); }

void FrameLabels::reserve(std::size_t frames) {
  name_of_.reserve(frames);
  sequences_.reserve(frames);
}

const std::string& FrameLabels::frameId(int index) const { return names_[name_of_.at(static_cast<std::size_t>(index))]; }

std::int64_t FrameLabels::sequence(int index) const { return sequences_.at(static_cast<std::size_t>(index)); }

std::size_t FrameLabels::memoryBytes() const {
  // A table node holds its key, value and link; the key's characters are in name_bytes_.
  constexpr std::size_t kNode = sizeof(void*) + sizeof(std::string) + sizeof(std::uint32_t) + sizeof(std::size_t);
  return name_of_.capacity() * sizeof(std::uint32_t) + sequences_.capacity() * sizeof(std::int64_t) +
         names_.capacity() * sizeof(std::string) + index_of_.bucket_count() * sizeof(void*) +
         index_of_.size() * kNode + name_bytes_;
}

bool FrameLabels::holds(int index, const std::string& frame_id, std::int64_t sequence) const {
  return index >= 0 && index < size() && sequence == sequences_[static_cast<std::size_t>(index)] &&
         frame_id == frameId(index);
}

}  // namespace mrs_vpr
