#pragma once

// The place links of a map's own frames, drive by drive: those build_map would have stored had it
// closed loops while it added each drive (a map built with --no-place-links, or by a release before
// place links).

#include "mrs_vpr/store/map_database.hpp"

namespace mrs_vpr {
namespace tools {

/// What linkDrives() did.
struct DriveLinking {
  int drives = 0;
  int questions = 0;
  int closures = 0;   ///< Accepted answers, each a link.
  int new_links = 0;  ///< Links the map did not hold yet, now stored.
};

/**
 * Closes loops over each drive of `map` (drive_starts.hpp; the first begins at frame 0) against the
 * frames before it, as build_map closes them over a traversal it adds (TraversalClosures), knowing the
 * links of the earlier drives, and stores the links the map does not hold yet, in one transaction.
 * `min_appearance_change` as the map's keyframes were kept at (the rule also tells repeated views).
 * Holds the map in memory.
 */
DriveLinking linkDrives(MapDatabase& map, double min_appearance_change);

}  // namespace tools
}  // namespace mrs_vpr
