#pragma once

#include <string>
#include <vector>

#include "mrs_vpr/match.hpp"
#include "mrs_vpr/parameters.hpp"

namespace mrs_vpr {

/**
 * The acceptance rule, one for every method, sequence length and map size.
 *
 * A query about a place that is not in the map still has a best end: the least bad of many wrong
 * ones. Its cost is an extreme of the costs of the wrong ends, and so is the runner-up's, so the two
 * lie close together on the scale of the wrong ends' spread: for n independent Gaussian costs the gap
 * between the two lowest exceeds d spreads with probability about exp(-d * sqrt(2 ln n)), i.e. below
 * 1e-4 at d = 3 for any map of 100 or more frames (and lower the larger the map). A place in the map
 * stands out from every other end by many spreads. The confidence is therefore the gap between the
 * best and its rival in units of the spread of this query's own costs: it needs no reference value,
 * and a threshold on it means the same whatever the method, sequence length, pooling or map size.
 */

/// Robust standard deviation of the finite costs: 1.4826 x their median absolute deviation, so that
/// the few ends near the true place do not inflate it. Reads every (size / kSpreadSamples)-th cost:
/// all of a table shorter than 2 x kSpreadSamples, and from kSpreadSamples to under twice that many
/// evenly spaced costs of a longer one, which estimates it to a few percent at any map size. 0 when
/// fewer than 3 costs are finite.
float costSpread(const std::vector<float>& costs);

/// Evenly spaced costs that costSpread reads at least from a long table (and fewer than twice as many).
constexpr int kSpreadSamples = 4096;

/// Fewest rivals (finite ends outside the answer's exclusion window) a confidence needs. The bound
/// above reaches 1e-4 at d = 3 only from about 100 ends; among a few dozen wrong places the least bad
/// one stands out by chance (on real frames, maps of 20 to 75 frames accepted 7% to 0.03% of the
/// queries about places outside them), so with fewer rivals nothing is accepted.
constexpr int kMinRivalEnds = 100;

/// (runner_up - best) / spread; 0 when any of them is not finite, the spread is 0 or there are
/// fewer than kMinRivalEnds `rivals`.
float distinctiveness(float best, float runner_up, float spread, int rivals);

/// Places (see placesAmong) from which sequence/accept_threshold applies as it is.
constexpr int kPlacesForPlainThreshold = 100;

/// The distinct places among `rivals` ends of a table whose ends lie `frames_per_end` reference frames
/// apart. Neighbouring ends are no independent chances: ends within match_exclusion / 2 frames of each
/// other (the half-width of the window that is the answer's own place) show one place.
int placesAmong(int rivals, int frames_per_end, int match_exclusion);

/**
 * The confidence an answer among `places` rival places needs (placesAmong): params.accept_threshold,
 * raised on maps of fewer than kPlacesForPlainThreshold places. For n places the bound above,
 * exp(-d sqrt(2 ln n)), keeps its value at 100 places when d grows by sqrt(ln 100 / ln n): by 1.41 at
 * 10 places, 1.07 at 50. (At the plain threshold, maps of 150 and 200 real frames accepted 5 and 1 of
 * 2526 queries at sequence length 50 about places outside them.)
 */
double requiredConfidence(int places, const SequenceParams& params);

/**
 * True when the answer's trajectory runs at the slowest or the fastest of the velocities searched
 * (when at least three are). The best fit then lies at the edge of the speeds the search assumes, and
 * the robot's true speed relative to the map may lie beyond it: a robot at half the map's speed, or
 * driving the route backwards, fits no trajectory, and the least bad wrong place can still stand out
 * by chance. On real frames, every such answer accepted at sequence length 50 was wrong (8 of 8 at
 * half the speed, 3 of 3 backwards), and no accepted answer at the map's own speed ran at a bound.
 */
bool atVelocityBound(const Match& match, const SequenceParams& params);

/// Sets match.accepted: a match was found, its confidence reaches requiredConfidence(), and its
/// trajectory is not at a velocity bound (atVelocityBound; such a match gets confidence 0, as one
/// among too few rivals does, and match.at_velocity_bound).
void applyAcceptance(Match& match, const SequenceParams& params);

/// For the user: "accepted", or why not ("no match found", too few rivals, a test sequence showing
/// one view again, confidence below the threshold, or a trajectory at a velocity bound), naming the
/// parameters involved.
std::string acceptanceVerdict(const Match& match, const SequenceParams& params);

}  // namespace mrs_vpr
