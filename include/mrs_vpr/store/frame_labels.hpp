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
  /// Undoes what prepareFor() added for a frame that was not admitted after all: a frame id that no
  /// frame holds is not kept (a camera that names each frame anew would otherwise grow it for ever).
  void cancelPrepared();
  /// Adds the next frame's labels.
  void append(const std::string& frame_id, std::int64_t sequence);
  /// Forgets every frame, and the memory they held.
  void clear();
  /// Room for `frames` frames in all.
  void reserve(std::size_t frames);

  int size() const { return static_cast<int>(sequences_.size()); }
  /// Frame `index`'s frame id and number; `index` must be in [0, size()).
  const std::string& frameId(int index) const;
  std::int64_t sequence(int index) const;
  /// Bytes held (allocated capacity; the frame ids' table estimated by its buckets and nodes).
  std::size_t memoryBytes() const;
  /// Whether frame `index` has these labels.
  bool holds(int index, const std::string& frame_id, std::int64_t sequence) const;

 private:
  std::vector<std::string> names_;                           ///< Distinct frame ids, in order of first use.
  std::unordered_map<std::string, std::uint32_t> index_of_;  ///< names_[index_of_[name]] == name.
  std::vector<std::uint32_t> name_of_;                       ///< Per frame: its frame id in names_.
  std::vector<std::int64_t> sequences_;                      ///< Per frame.
  std::size_t name_bytes_ = 0;      ///< What names_ and index_of_'s keys hold, beyond their objects.
  bool prepared_a_new_name_ = false;  ///< The last prepareFor() added names_.back(), which no frame holds yet.
};

}  // namespace mrs_vpr
