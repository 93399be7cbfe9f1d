#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "mrs_vpr/match_explanation.hpp"
#include "mrs_vpr/place_recognizer.hpp"

namespace mrs_vpr {
namespace visualization {

/// Where each part of a match image lies. The width is fixed; the height grows with MRS's levels.
struct MatchImageLayout {
  static constexpr int kWidth = 512;
  cv::Size size;
  cv::Rect query_thumbnail;      ///< The localised test frame's descriptor, scaled up.
  cv::Rect reference_thumbnail;  ///< The matched reference frame's, beside it.
  cv::Rect band;                 ///< The difference band: test frames down, reference frames across.
  cv::Rect band_caption;         ///< Which frames the band shows.
  std::vector<cv::Rect> levels;  ///< One strip per MRS level (the whole map across), coarsest first.
  cv::Rect verdict;              ///< Method, answer, confidence, accepted or not.
  cv::Rect map_status;           ///< A line about the map the caller gives (keyframes, frames skipped).
};

/// The layout of an image of an answer with `levels` MRS levels (0 for seqslam).
MatchImageLayout matchImageLayout(int levels);

/**
 * The picture of one answer, BGR (CV_8UC3, matchImageLayout(explanation.levels.size()).size):
 * the localised test frame beside the matched reference frame (their descriptors), the band of
 * differences around the match (each reference frame's column standardised; dark = similar) with the best trajectory
 * dashed in red, for MRS one strip per level with its particles (yellow, the lowest-cost one green) and the answer
 * (red) over the whole map, and the confidence with the verdict (green accepted, red not). No ROS: the node publishes
 * it, a tool may write it to a file.
 */
/// `map_status` is written on the last line (the node says how many frames it skipped as too similar).
cv::Mat renderMatchImage(const MatchExplanation& explanation, const PlaceAnswer& answer,
                         const std::string& map_status = {});
/// The same into `image`, whose buffer is reused when it has the size already: a caller that draws
/// often (the node) avoids fresh pages, which after a large query cost more than the drawing itself.
void renderMatchImage(const MatchExplanation& explanation, const PlaceAnswer& answer, cv::Mat& image,
                      const std::string& map_status = {});

/// The pixel where renderMatchImage draws the trajectory's point for test frame `test_frame`.
cv::Point trajectoryPixel(const MatchExplanation& explanation, int test_frame);

/// Whether that point is drawn: the trajectory is dashed (8 dashes), so that the cells it follows
/// stay visible between them.
bool trajectoryDrawnAt(const MatchExplanation& explanation, int test_frame);

/// Colours of the picture (BGR), for its users and tests.
const cv::Scalar kTrajectoryColour(0, 0, 255);
const cv::Scalar kParticleColour(0, 255, 255);
const cv::Scalar kBestParticleColour(0, 255, 0);

}  // namespace visualization
}  // namespace mrs_vpr
