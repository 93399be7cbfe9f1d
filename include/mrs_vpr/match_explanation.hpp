#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/match.hpp"
#include "mrs_vpr/mrs_matcher.hpp"
#include "mrs_vpr/parameters.hpp"

namespace mrs_vpr {

/**
 * What a picture of one answer needs (see visualization/match_image.hpp), kept small: descriptors
 * rather than frames, and a band of the difference matrix around the answer rather than all of it.
 * PlaceRecognizer fills it only when asked, so a query without it costs nothing more.
 */
struct MatchExplanation {
  /// Picture of the descriptor of the test frame the answer localises (the newest one when causal),
  /// CV_8UC1, as its front end draws it (FrontEnd::picture): a thumbnail is its own image, HOG's
  /// histograms are drawn as edges on the window's grid.
  cv::Mat query_thumbnail;
  /// The same for the matched reference frame; empty when there is no match.
  cv::Mat reference_thumbnail;
  /**
   * Raw differences (CV_32FC1) of every `band_step`-th test frame from `band_first_row` (rows, oldest
   * first) against every `band_step`-th reference frame from `band_first` (columns): the stretch of
   * the map the best trajectory crosses, with a margin. Both grids pass through the answer's cell.
   * Empty when there is no match.
   */
  cv::Mat band;
  int band_first = 0;
  int band_first_row = 0;
  int band_step = 1;
  /// The best straight trajectory ending at the answer: for test frame t (index t), the reference
  /// frame it visits. Empty when there is no match.
  std::vector<int> trajectory;
  /// Its velocity [reference frames per test frame].
  double velocity = 0.0;
  int reference_frames = 0;  ///< Frames searched: the extent of the level traces.
  int query_frames = 0;      ///< Frames of the test sequence.
  int anchor = 0;            ///< Test frame the answer localises.
  /// MRS only: each level's particles when it ended, coarsest first (empty for seqslam).
  std::vector<MrsLevelTrace> levels;
};

/**
 * Fills a MatchExplanation (all but `levels`) for `match`, the answer of a search of `query` in
 * `reference` with `params`. Costs at most kMaxBandSide^2 + velocities * query.count descriptor
 * comparisons, whatever the map's size: the band is subsampled to at most kMaxBandSide rows and
 * columns. The trajectory is the searched velocity whose straight line to the answer has the
 * lowest mean raw difference; `descriptor` gives the front end that draws the descriptors.
 */
MatchExplanation explainMatch(SequenceView reference, SequenceView query, const Match& match,
                              const SequenceParams& params, const DescriptorParams& descriptor);

/// The band is at most this many cells on either side, so that explaining stays cheap on long queries.
constexpr int kMaxBandSide = 160;

}  // namespace mrs_vpr
