#pragma once

#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/frame_range.hpp"
#include "mrs_vpr/match.hpp"
#include "mrs_vpr/repeated_views.hpp"

namespace mrs_vpr {

/**
 * Whether a test sequence of the map's newest keyframes (`test`) turned back before the keyframe its
 * answer localises (`localised_row`): a robot that turned back or backed up within it. The search's
 * trajectories run forwards, so such a sequence is matched by its part before the turn, and an answer
 * about a keyframe after the turn extrapolates that part past it: on Nordland frames driven out and
 * back (doc/experiments/turn_back.py), 3 accepted answers named places 17 to 21 frames ahead of the
 * robot, and 2 named places 617 and 620 frames away where the map's recording resumed elsewhere after
 * the turn's place. An answer about a keyframe before the turn is the way out's, and stands.
 *
 * Keyframes hide the first part of the way back (a frame like one of the last
 * AppearanceKeyframes::kRecentKeyframes keyframes is none), so the way back's keyframes show the views
 * of keyframes farther back. A test keyframe returns when its view differs by less than
 * `min_appearance_change` (`views`) from a keyframe more than kRecentKeyframes before it and no earlier
 * than kRecentKeyframes plus the sequence's length before the sequence: the way back's k-th keyframe
 * shows about the view of the keyframe kRecentKeyframes + k before the turn, so that reach finds every
 * keyframe of the way back while the sequence still holds the way out. The sequence turned back before
 * the localised keyframe when more than half of the keyframes from it to the newest return: after a
 * turn all of them do, while in a forward drive a view merely like one seen 17 to 56 keyframes before (a
 * dark tunnel, a row of alike buildings) makes one to three keyframes of the sequence return. A robot
 * going round a loop of a few dozen keyframes returns too, but forwards: the places its keyframes show
 * again follow on, whereas the way back's run backwards, so it turns back only where the newest
 * returning keyframe shows a place passed before that of the oldest (or one keyframe returns alone).
 * Judged, as RepeatedViews, on the scale of the map's camera, on at most RepeatedViews::kMaxJudged
 * keyframes spread over the sequence.
 */
bool returnsToPassedPlace(const DescriptorSequence& map, FrameRange test, int localised_row,
                          const RepeatedViews& views);

/// Takes back the acceptance of `match` when its test sequence turned back before the localised keyframe,
/// and says so (Match::turned_back). Judges only accepted answers: the comparisons change nothing else.
void refuseTurnsBack(Match& match, const DescriptorSequence& map, FrameRange test, int localised_row,
                     const RepeatedViews& views);

}  // namespace mrs_vpr
