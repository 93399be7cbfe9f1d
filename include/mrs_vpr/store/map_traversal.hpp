#pragma once

// What a map records of the traversal its frames were kept of, and what a mismatch of keyframing
// between a map and the frames asked about costs.

#include <cstdint>
#include <optional>
#include <string>

namespace mrs_vpr {

/// The traversal a map's frames were kept of, as a map records it (MapDatabase::setTraversal).
struct MapTraversal {
  /// Its frames, numbered 0 .. frames - 1: those after the last keyframe are still frames of it.
  std::int64_t frames = 0;
  /// The appearance change at which its keyframes were kept (RecognizerParams::min_appearance_change,
  /// 0: every frame); nullopt when they were kept otherwise (by travel).
  std::optional<double> min_appearance_change;
};

/// The number of the frame offered after the one numbered `last` (-1: none yet): `last` + 1, but at
/// least `map`'s recorded frames, so that frames after its last keyframe keep their numbers; it stays
/// at the largest number rather than wrap (a crafted file).
std::int64_t nextFrameNumber(std::int64_t last, const std::optional<MapTraversal>& map = std::nullopt);

/**
 * Numbers frames offered after a map's own, so that no new number repeats one of the map's: shown the
 * map's frame numbers in order, it goes on after the largest, a frame without one (-1, as in maps
 * saved before frames were numbered) counting as its index, and after the traversal the map records.
 */
class FrameNumbering {
 public:
  /// The next of the map's frames has `number` (-1: none).
  void see(std::int64_t number);
  /// The number of the first frame offered after the map's.
  std::int64_t next(const std::optional<MapTraversal>& map = std::nullopt) const;

 private:
  std::int64_t seen_ = 0;
  std::int64_t largest_ = -1;
};

/**
 * A warning when the frames asked about are keyframed at `min_appearance_change` (named `setting` in
 * the words of the caller: "~min_appearance_change", "--min-appearance-change") and the map's were
 * kept at another appearance change; empty when they agree or the map records none. The test
 * sequences then lie on another scale than the map's, which loses answers and accepts wrong ones
 * (Nordland winter against a summer map kept at 0.4, queries at 0: top-1 0.853 against 0.991, and 11
 * wrong accepted against none).
 */
std::string keyframingMismatch(const std::optional<MapTraversal>& map, double min_appearance_change,
                               const std::string& setting);

}  // namespace mrs_vpr
