#pragma once

// What the camera-drive rows list on stderr when asked: MRS_VPR_SHOW_MISSED, the stretches of a revisit
// that no closure confirmed, and MRS_VPR_SHOW_FALSE, each wrong closure with the keyframes around it.

#include <string>

#include "mrs_vpr/match.hpp"
#include "replayed_drive.hpp"

namespace mrs_vpr {
namespace benchmark {

/// One answer as MRS_VPR_SHOW_MISSED lists it: the localised route frame, the confidence, and A
/// (accepted), x (wrong), b (at a velocity bound) or r (repeated view).
std::string answerNote(int route_frame, const Match& match, bool right);

/// MRS_VPR_SHOW_MISSED: each stretch of the revisit that no accepted right answer confirmed, with its
/// route frames; how many of its frames stood, were half-speed copies, were driven at double speed,
/// or show route frames that the map drive drove at double or half speed; whether a keyframe came; and
/// the answers about its keyframes. Stretches without a keyframe are confirmed only by a closure
/// restated for their stop (standing_frames.hpp).
void printMissedStretches(const Drive& map, const Drive& revisit, const DriveCounts& count);

/// MRS_VPR_SHOW_FALSE: a wrong closure, with the route frames of the test sequence's keyframes (* the
/// localised one) and of the map's keyframes around the answer (* the answer): where their spacing
/// differs, and how. The test sequence is keyframes [end - recent, end); `drive_frame` is the drive's
/// frame at which it was asked.
void printFalseClosure(const std::string& method, const std::string& drive, int drive_frame, const ReplayLog& log,
                       const Match& match, int end, int recent, int anchor);

}  // namespace benchmark
}  // namespace mrs_vpr
