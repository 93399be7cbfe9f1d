#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

namespace mrs_vpr {

/**
 * What a map frame's image said of itself besides its descriptor and stamp: its camera frame
 * (StoredFrame::frame_id) and its number (StoredFrame::sequence), frame by frame in the map's order.
 * The recognizer keeps neither; a map saved from memory, and an answer about a map frame, need both.
 * A camera's frames share one frame id, which is held once: about 12 bytes a frame.
 */
class FrameLabels {
 public:
  /// Makes room for one more frame with `frame_id` (it may allocate, growing geometrically), so that
  /// the append() of that frame that follows cannot fail: a frame is admitted to a map between them.
  void prepareFor(const std::string& frame_id);
  /// Adds the next frame's labels.
  void append(const std::string& frame_id, std::int64_t sequence);
  /// Forgets every frame, and the memory they held.
  void clear();
  void reserve(std::size_t frames);

  int size() const { return static_cast<int>(sequences_.size()); }
  /// Frame `index`'s frame id and number; `index` must be in [0, size()).
  const std::string& frameId(int index) const;
  std::int64_t sequence(int index) const;
  /// Bytes held (allocated capacity).
  std::size_t memoryBytes() const;
  /// Whether frame `index` has these labels.
  bool holds(int index, const std::string& frame_id, std::int64_t sequence) const;

 private:
  std::vector<std::string> names_;                           ///< Distinct frame ids, in order of first use.
  std::unordered_map<std::string, std::uint32_t> index_of_;  ///< names_[index_of_[name]] == name.
  std::vector<std::uint32_t> name_of_;                       ///< Per frame: its frame id in names_.
  std::vector<std::int64_t> sequences_;                      ///< Per frame.
};

}  // namespace mrs_vpr
