#pragma once

#include <cstddef>
#include <mutex>
#include <vector>

#include "mrs_vpr/frame_range.hpp"

namespace mrs_vpr {

/**
 * Which map frames show one place, as the map's own accepted loop closures linked them: a map that
 * grows as the robot drives holds a place once per visit.
 *
 * The confidence of an answer is how far it beats its best rival elsewhere in the map. A place the map
 * holds twice in the same conditions is its own rival: the answer names one visit, the other costs
 * about as much, and from the third visit on a right answer is refused (doc/limitations.md). The
 * frames an accepted closure linked to the answer's place show that place, not another one, and are
 * no rivals (samePlaceAs()).
 *
 * Each link joins a frame to the place of an older one; a place is named by its oldest frame (its
 * first visit). Only frames linked so far are held (4 bytes a frame up to the newest linked one).
 * Thread-safe: queries read while continuous mode links.
 */
class PlaceLinks {
 public:
  /// An accepted loop closure: map frame `frame` shows the place of map frame `reference`.
  void link(int frame, int reference);
  /// Where other visits show the place of the window of `half` frames around `frame`: the frames that
  /// show a place one of the window's frames shows (the first visit's frames there, and those linked to
  /// them), each visit's run of them widened to the window's width where it is narrower (where few of
  /// its keyframes were linked). The window itself is left out. Ranges sorted, apart, clipped at 0;
  /// none while nothing is linked.
  std::vector<FrameRange> samePlaceAs(int frame, int half) const;
  /// Frames linked to an older frame's place.
  int linkedFrames() const;
  /// Bytes held: 4 a frame up to the newest linked one.
  std::size_t memoryBytes() const;
  /// Forgets every link (the map was reset or replaced).
  void clear();

 private:
  int placeOfLocked(int frame) const;

  mutable std::mutex mutex_;
  std::vector<int> place_;  ///< The first-visit frame each frame shows (itself when not linked).
  int linked_ = 0;
};

}  // namespace mrs_vpr
