#pragma once

#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/frame_range.hpp"
#include "mrs_vpr/match.hpp"
#include "mrs_vpr/repeated_views.hpp"

namespace mrs_vpr {

/**
 * Whether the map holds, near an answer (`near`), frames of the test sequence's own recording (`test`,
 * the map's newest keyframes), as when one recording is added to the map twice (a bag played again):
 * - a test keyframe's descriptor, byte for byte, at the same stamp or where either stamp is 0 (an
 *   unstamped replay); not at two known times, as generated frames without noise show one view twice on
 *   two visits (a replay stamped anew on arrival is therefore not found); or
 * - where the second pass kept other frames as keyframes than the first (the keyframe rule starts from
 *   another state), a test keyframe whose stamp lies between two consecutive map keyframes no farther
 *   apart in time than the test sequence spans, and whose view differs by less than
 *   `min_appearance_change` (`views`) from one of the kRecentKeyframes keyframes on either side: a
 *   frame the first pass left out as no new view. Stamps alone cannot tell: another traversal may run
 *   on the same clock (simulated time starts at 0 every run); it counts only where it shows the same
 *   view at the same time. A zero stamp (not known) encloses nothing.
 * Costs one hash of each frame of both ranges, and view comparisons only for enclosed test keyframes.
 */
bool holdsOwnRecording(const DescriptorSequence& map, FrameRange test, FrameRange near, const RepeatedViews& views);

/// Takes back the acceptance of `match` when the map holds frames of the test sequence's own recording
/// within `reach` frames of its answer (among the first `searched_frames`), and says so
/// (Match::same_recording): a frame that finds itself is no loop closure. Judges only accepted answers.
void refuseSameRecording(Match& match, const DescriptorSequence& map, FrameRange test, int searched_frames, int reach,
                         const RepeatedViews& views);

}  // namespace mrs_vpr
