#pragma once

#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/parameters.hpp"
#include "mrs_vpr/trajectory_search.hpp"

namespace mrs_vpr {

/**
 * Places an answer by a flexible path instead of the straight trajectory that found it.
 *
 * The searches score straight trajectories, one speed per sequence. Where the robot's speed changed
 * within the sequence relative to the map's (a stop that keyframing left, a slow or a fast stretch,
 * keyframes chosen at other places on the two traversals), the best straight trajectory passes near
 * the place but ends a few frames off. So the answer is placed again: the lowest-cost path through the
 * contrast-enhanced differences within `slack` frames of that trajectory, advancing 1 reference frame a
 * test frame at no cost, 0 or 2 at a cost of kStepPenalty (so it stays or skips only where that pays),
 * and the answer becomes the path's frame at the localised test frame.
 *
 * Only the answer's frame moves: its confidence, and so acceptance, are the straight search's, which
 * judged the place among all the others. Costs about query.count * (2 * slack + 1 + contrast window)
 * descriptor comparisons.
 */

/// Cost of a step of 0 or 2 reference frames, in contrast-enhanced units (standard deviations).
constexpr float kStepPenalty = 1.0F;

/// The reference frame of the anchor test frame on the best flexible path near the straight
/// trajectory of `velocity` ending at `end` (rows of `query` per `rows`); `end` when slack is 0 or
/// the band leaves the reference.
int realignEnd(SequenceView reference, SequenceView query, const SequenceRows& rows, int end, double velocity,
               int slack, int contrast_window);

}  // namespace mrs_vpr
