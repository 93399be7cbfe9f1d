#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace mrs_vpr {

/**
 * Places along a recorded route, for ground truth: consecutive route frames where the recording
 * camera stood still are one place.
 *
 * Route frames are moments of a recording, not places. In the shared Nordland route the train stands
 * (in stations, at signals) for up to 50 consecutive frames: 211 of its 1782 steps in 21 runs, whose
 * frames differ by about a grey level. Counted in route frames, an answer that puts the robot at
 * another frame of the same station is "wrong" by dozens of frames although it names the very place;
 * counted in places it is right, and an answer one place off is still one place off.
 *
 * A step between consecutive route frames is standing when its mean absolute grey-level difference is
 * below `standing_share` times the median step of the route, in every traversal: the median step is a
 * moving camera's, so the scale comes from the data. At kStandingShare = 0.1 the shared Nordland
 * steps marked standing differ by under 2.6 (summer) and 3.0 (winter) grey levels, against medians of
 * 26 and 30. The boundary is not sharp: a train slowing into a station changes its view ever less, so
 * a station's first and last frames may fall either side.
 */
constexpr double kStandingShare = 0.1;

/// The place of each route frame (0, 1, ...: a place more for each step that is not standing in
/// every traversal). `traversals`: the route's images in route order, one vector per traversal, all
/// the same length and each image of a type toGrey takes (descriptor.hpp) and the size of that
/// traversal's first. Throws std::invalid_argument when the traversals are empty or differ in length,
/// an image differs in size or its type is not taken, or standing_share is not in [0, 1).
std::vector<int> routePlaces(const std::vector<const std::vector<cv::Mat>*>& traversals,
                             double standing_share = kStandingShare);

/// The place of each of `route_frames` (indices into `places`, as routePlaces returns them).
/// Throws std::out_of_range for a route frame outside `places`.
std::vector<int> placesOf(const std::vector<int>& route_frames, const std::vector<int>& places);

}  // namespace mrs_vpr
