#pragma once

#include <cstdint>

#include <opencv2/core.hpp>

#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/stamp.hpp"

namespace mrs_vpr {

/// Keyframes a trail holds at least: a test sequence of up to this many, and the keyframes before it
/// that the turn-back rule reads, fit in it (3 MB of HOG descriptors).
constexpr int kTrailKeyframes = 4096;

/**
 * The camera's newest keyframes while the map stays as it is (a fixed map, localisation only): what
 * the questions about the newest keyframes ask about instead of the map's own frames. Keyframes are
 * counted from the first appended, so that a question can name where its sequence ends whatever was
 * dropped; the oldest are dropped in one piece once twice `keep` are held. Not thread-safe:
 * PlaceRecognizer locks it.
 */
class Trail {
 public:
  Trail(int descriptor_size, int keep = kTrailKeyframes);

  /// Appends a keyframe (its bytes are copied). Throws std::invalid_argument for another size.
  void append(const cv::Mat& descriptor, Stamp stamp);
  /// Keyframes appended: the end of the newest.
  std::int64_t size() const { return dropped_ + held_.size(); }
  /// The oldest keyframe held, counted as size() counts.
  std::int64_t oldest() const { return dropped_; }
  /// A copy of keyframes [begin, end), counted as size() counts. Throws std::invalid_argument unless
  /// they are held.
  DescriptorSequence copy(std::int64_t begin, std::int64_t end) const;
  /// Bytes held (capacity).
  std::size_t memoryBytes() const { return held_.memoryBytes(); }

 private:
  int keep_;
  DescriptorSequence held_;
  std::int64_t dropped_ = 0;
};

}  // namespace mrs_vpr
