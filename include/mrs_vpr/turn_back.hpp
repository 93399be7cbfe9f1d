#pragma once

#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/frame_range.hpp"
#include "mrs_vpr/match.hpp"
#include "mrs_vpr/repeated_views.hpp"

namespace mrs_vpr {

/// How far the turn-back rule looks back at most, in units of a sequence's keyframes plus the last
/// AppearanceKeyframes::kRecentKeyframes: a bound on its cost where `recent_exclusion` is large.
constexpr int kReachInSequenceLengths = 4;

/**
 * Whether the keyframe a test sequence's answer localises (`localised_row` of `test`, the map's newest
 * keyframes) lies where the robot went back over its own path: a robot that turned back or backed up.
 * The search's trajectories run forwards, so such a sequence is matched by its part before the turn,
 * and an answer about a keyframe after the turn extrapolates that part past it: on Nordland frames
 * driven out and back (doc/experiments/turn_back.py), 3 accepted answers named places 17 to 21 frames
 * ahead of the robot, and 2 named places 617 and 620 frames away where the map's recording resumed
 * elsewhere after the turn's place. An answer about a keyframe before the turn is the way out's, and
 * stands.
 *
 * Keyframes hide the first part of the way back (a frame like one of the last
 * AppearanceKeyframes::kRecentKeyframes keyframes is none), so the way back's keyframes show the views
 * of keyframes farther back: the k-th about that of the keyframe kRecentKeyframes + k before the turn.
 * A test keyframe returns when its view differs by less than `min_appearance_change` (`views`) from a
 * keyframe more than kRecentKeyframes before it and no earlier than the keyframes before the sequence
 * that the search leaves out (`unsearched`: recent_exclusion), or kRecentKeyframes plus the sequence's
 * length if more, and at most kReachInSequenceLengths times that. Each returning keyframe is taken to show
 * the oldest keyframe within reach that it looks like, so that a robot driving forward again after
 * backing up is judged by its way out, which it follows, not by its way back. The localised keyframe
 * lies on a way back when
 * - more than half of the keyframes from it to the newest return: after a turn all of them do, while
 *   in a forward drive a view merely like one seen a few dozen keyframes before (a dark tunnel, a row of
 *   alike buildings) makes one to three return; and
 * - judged by the returning keyframes next to it, the robot went back there: it returns itself, to a
 *   place before that of the returning keyframe judged before it or after that of the one after it, or
 *   it does not return (noise changed its view) but lies between two returning keyframes that step
 *   back. A robot going round a small loop returns too, but onwards; in a zig-zag only the keyframes of
 *   the ways back step back. One returning with no other is taken as a turn just begun (with the
 *   causal alignment, the newest keyframe only).
 * Judged, as RepeatedViews, on the scale of the map's camera, on at most RepeatedViews::kMaxJudged
 * keyframes spread over the sequence.
 */
bool returnsToPassedPlace(const DescriptorSequence& map, FrameRange test, int localised_row, int unsearched,
                          const RepeatedViews& views);

/// Takes back the acceptance of `match` when its localised keyframe lies on a way back, and says so
/// (Match::turned_back). Judges only accepted answers: the comparisons change nothing else.
void refuseTurnsBack(Match& match, const DescriptorSequence& map, FrameRange test, int localised_row, int unsearched,
                     const RepeatedViews& views);

}  // namespace mrs_vpr
