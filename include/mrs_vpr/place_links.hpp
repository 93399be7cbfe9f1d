#pragma once

#include <cstddef>
#include <mutex>
#include <vector>

#include "mrs_vpr/frame_range.hpp"

namespace mrs_vpr {

/// An accepted loop closure as the map keeps it: map frame `frame` shows the place of map frame `reference`.
struct PlaceLink {
  int frame = 0;
  int reference = 0;
};

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
 * A map database keeps the links with the frames (persistent_map.hpp): the links made since it last
 * took them wait in a log (takeUnsaved()), and a map read back gets them all at once (placesOf(),
 * adopt()). The links that joined places are kept as made (8 bytes each), so that one found wrong
 * afterwards can be forgotten (linksOfClosure(), forget()). Thread-safe: queries read while
 * continuous mode links.
 */
class PlaceLinks {
 public:
  /// An accepted loop closure: map frame `frame` shows the place of map frame `reference`. Returns
  /// whether it joined two places (false when they were one already). Throws std::invalid_argument
  /// for a negative frame.
  bool link(int frame, int reference);
  /// Where other visits show the place of the window of `half` frames around `frame`: the frames that
  /// show a place one of the window's frames shows (the first visit's frames there, and those linked to
  /// them), each visit's run of them widened to the window's width where it is narrower (where few of
  /// its keyframes were linked). The window itself is left out. Ranges sorted, apart, clipped at 0;
  /// none while nothing is linked.
  std::vector<FrameRange> samePlaceAs(int frame, int half) const;
  /// Frames linked to an older frame's place.
  int linkedFrames() const;
  /// Bytes held: 4 a frame up to the newest linked one, and 8 a link kept.
  std::size_t memoryBytes() const;
  /// Forgets every link (the map was reset or replaced), and the log of those not yet stored.
  void clear();

  /// The places that `links` make among frames [0, frames), as link() would make them one by one, in
  /// time linear in both (a million linked frames replayed one by one would take hours). Frames
  /// beyond the newest linked one are left out. Throws std::invalid_argument for a link outside them.
  static std::vector<int> placesOf(const std::vector<PlaceLink>& links, int frames);
  /// Forgets every link (clear()) and takes `places`, of placesOf(`links`), and `links` instead: a map
  /// read back. Moves them in, so that it cannot fail for want of memory.
  void adopt(std::vector<int>&& places, std::vector<PlaceLink>&& links) noexcept;

  /// The kept links by which an accepted loop closure put map frame `frame` in the place of map frame
  /// `reference`: those from `frame` to a frame of that place (the closure's own link, or, in a map
  /// saved without its links as made, the link to the place's first frame). Empty when there is none:
  /// the closure linked nothing (the frames were one place already) or its link was forgotten.
  std::vector<PlaceLink> linksOfClosure(int frame, int reference) const;
  /// Forgets `forgotten` (of linksOfClosure(): a closure that the robot's back end refused): the
  /// places become those the other links make, and the log of links not yet stored loses them too.
  void forget(const std::vector<PlaceLink>& forgotten);
  /// The links among frames [0, frames) as few links that make the same places again (each linked
  /// frame to its place's first frame), for a copy of the map.
  std::vector<PlaceLink> asLinks(int frames) const;

  /// From now on, each link() that joins two places is also kept in a log until takeUnsaved() (for a
  /// map database; without one, nothing is logged).
  void keepUnsaved();
  /// The links made since the last call, in order, and an empty log.
  std::vector<PlaceLink> takeUnsaved();

 private:
  int placeOfLocked(int frame) const;

  mutable std::mutex mutex_;
  std::vector<int> place_;  ///< The first-visit frame each frame shows (itself when not linked).
  std::vector<PlaceLink> made_;  ///< The links that joined two places, in order: place_ is placesOf() them.
  int linked_ = 0;
  bool keep_unsaved_ = false;
  std::vector<PlaceLink> unsaved_;
};

}  // namespace mrs_vpr
