#pragma once

namespace mrs_vpr {

/**
 * Throws std::invalid_argument when a test sequence of the map's own frames [first, end) holds both
 * frames of a loaded map (those before `loaded_frames`) and frames added since. The two were taken on
 * two drives, so their junction is no place; but its sequence can look like another junction the map
 * holds (visits appended one after another) or like a stretch of either drive, and an accepted answer
 * there would be a false loop closure, and link its place. A sequence of either side alone is asked
 * about as always; with no map loaded (`loaded_frames` 0) every sequence is. A sequence beginning before
 * the map (`first` < 0) is the caller's to refuse.
 */
void refuseSequenceAcrossLoadedMap(long long first, long long end, long long loaded_frames);

}  // namespace mrs_vpr
