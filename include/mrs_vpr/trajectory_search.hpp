#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "mrs_vpr/frame_range.hpp"
#include "mrs_vpr/match.hpp"
#include "mrs_vpr/parameters.hpp"
#include "mrs_vpr/place_links.hpp"
#include "mrs_vpr/query_stop.hpp"

namespace mrs_vpr {

/// The velocities tried: velocity_min, +step, ... up to velocity_max (inclusive, rounding-safe).
std::vector<double> velocities(const SequenceParams& params);

/// Rows of a test sequence inside a difference matrix and the row whose reference frame is reported.
struct SequenceRows {
  int first = 0;   ///< Oldest test frame.
  int last = 0;    ///< Newest test frame.
  int anchor = 0;  ///< Frame localised: `last` when causal, the middle when centred.
};

/// Rows of the sequence that localises query frame `frame`; first < 0 or last >= rows when incomplete.
SequenceRows sequenceRowsFor(int frame, const SequenceParams& params);

/// Rows of a whole test sequence of `count` frames: anchored at its newest frame when causal, at
/// frame count / 2 when centred (the same frame sequenceRowsFor centres on).
SequenceRows wholeSequenceRows(int count, WindowAlignment alignment);

/// For every anchor column: the lowest trajectory cost (infinity when no trajectory fits) and the
/// velocity that achieved it.
struct AnchorCosts {
  std::vector<float> cost;
  std::vector<float> velocity;
};

/// Costs of all straight trajectories through `enhanced` (see searchTrajectories), per anchor column.
AnchorCosts costsByAnchor(const cv::Mat& enhanced, const SequenceRows& rows, const std::vector<double>& velocities,
                          const QueryStop* stop = nullptr);

/// The same through rows held apart (`enhanced_rows[t]`: `columns` values of row t) into `costs`,
/// whose storage is reused. Throws QueryStopped when `stop` asks to stop (checked per block of anchors).
void costsByAnchor(const std::vector<const float*>& enhanced_rows, int columns, const SequenceRows& rows,
                   const std::vector<double>& velocities, AnchorCosts& costs, const QueryStop* stop = nullptr);

/**
 * Brute-force straight-trajectory search through an enhanced difference matrix (test frames x
 * reference frames): for every anchor reference column j and velocity v, the trajectory visits
 * column j + round(v * (t - anchor)) at row t; its cost is the mean of the cells it visits. Only
 * trajectories that stay inside the matrix count. Returns the best anchor column scored by
 * scoreFromCosts (runner-up outside +-match_exclusion/2 of the best); acceptance is the caller's.
 */
Match searchTrajectories(const cv::Mat& enhanced, const SequenceRows& rows, const SequenceParams& params,
                         const QueryStop* stop = nullptr, const PlaceLinks* links = nullptr);

/**
 * The ends of a table of `columns` ends that are the answer's own place, not its rivals: those within
 * exclusion/2 of `winner`, and with `links` those where the map shows its place on other visits
 * (PlaceLinks::samePlaceAs of its frame, within the same half-width). Ends lie `frames_per_end` map
 * frames apart (a pooled table's). Sorted, apart, within [0, columns); the winner's window first
 * among them in its order.
 */
std::vector<FrameRange> ownPlaceEnds(int winner, int exclusion, int columns, const PlaceLinks* links = nullptr,
                                     int frames_per_end = 1);

/// The lowest of the costs outside `own` (ownPlaceEnds), and how many of them are finite.
struct Rivals {
  float lowest = 0.0F;
  int finite = 0;
};
Rivals rivalsOutside(const std::vector<float>& cost_by_anchor, const std::vector<FrameRange>& own);

/// Scores `winner` against the rest: best = lowest cost within exclusion/2 of it, runner-up = lowest
/// cost outside ownPlaceEnds (with `links`, the answer's place on other visits is no rival); score =
/// best / runner-up, confidence = (runner-up - best) / costSpread(all), 0 with fewer than kMinRivalEnds
/// finite rival ends; rival_places = placesAmong(those ends, 1, exclusion).
Match scoreAround(const std::vector<float>& cost_by_anchor, int winner, int exclusion,
                  const PlaceLinks* links = nullptr, int frames_per_end = 1);

/// Picks the lowest cost (infinity = no trajectory) and scores it against its rivals, as scoreAround does.
Match scoreFromCosts(const std::vector<float>& cost_by_anchor, int exclusion, const PlaceLinks* links = nullptr);
/// scoreFromCosts of a table of ends and velocities; the answer's velocity is its end's.
Match scoreAnchorCosts(const AnchorCosts& costs, int exclusion, const PlaceLinks* links = nullptr);

/// Up to `count` ends with the lowest finite costs, lowest first, each more than `separation`
/// ends from every one chosen before it: the distinct places a table of end costs suggests.
std::vector<int> distinctMinima(const std::vector<float>& cost_by_anchor, int separation, int count);

}  // namespace mrs_vpr
