#pragma once

#include <vector>

#include "mrs_vpr/frame_range.hpp"
#include "mrs_vpr/match.hpp"
#include "mrs_vpr/trajectory_search.hpp"

namespace mrs_vpr {

/**
 * Drive starts: map frames that begin a drive which does not continue the frame before them, as the
 * camera's first keyframe after a loaded map, or the first frame of a visit appended to a map. Their
 * junction with the frame before is no place. Yet a sequence across it can look like one: its part on
 * one side matches a stretch the other map holds, and its other part is as good as any. On Nordland, a
 * map of summer 0-799 loaded and winter 600-1782 driven after it accepted one such answer: winter 801,
 * on ground just beyond the map, went to winter 605 (confidence 3.41), whose trajectory ran from the
 * loaded map's last frames, which show winter 790-799's places, into the drive's first.
 *
 * `starts` are sorted map frames; frame 0 begins the map and is no junction.
 */

/// Adds `frame` to the sorted `starts` unless they hold it already or it is frame 0 (the map's
/// beginning, no junction); returns whether it was added. Throws std::invalid_argument for a
/// negative frame.
bool insertDriveStart(std::vector<int>& starts, int frame);

/// Throws std::invalid_argument when test frames [test.begin, test.end), the map's own, hold frames
/// on both sides of one of `starts`: two drives, asked about as if they were one.
void refuseTestSequenceAcrossDrives(FrameRange test, const std::vector<int>& starts);

/// Map frames [begin, end) of an answer's trajectory: those its straight path through the placed frame
/// (Match::reference_index, at row `rows.anchor`) visits at its velocity, from row `rows.first` to
/// `rows.last`; at the searched velocity (`velocities`, when given) nearest the answer's. A path
/// realigned within sequence/alignment_slack may stray that far from it.
FrameRange trajectoryFrames(const Match& match, const SequenceRows& rows, const std::vector<double>& velocities = {});

/// Takes back the acceptance of `match` when its trajectory (trajectoryFrames) holds map frames on both
/// sides of one of `starts`, and says so (Match::across_drives). Judges only accepted answers.
void refuseAcrossDrives(Match& match, const SequenceRows& rows, const std::vector<int>& starts,
                        const std::vector<double>& velocities = {});

}  // namespace mrs_vpr
