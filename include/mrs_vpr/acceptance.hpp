#pragma once

#include <vector>

#include "mrs_vpr/match.hpp"

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
/// the few ends near the true place do not inflate it. Reads at most kSpreadSamples evenly spaced
/// costs, which estimates it to a few percent at any map size. 0 when fewer than 3 costs are finite.
float costSpread(const std::vector<float>& costs);

/// Costs read by costSpread at most.
constexpr int kSpreadSamples = 4096;

/// Fewest rivals (finite ends outside the answer's exclusion window) a confidence needs. The bound
/// above reaches 1e-4 at d = 3 only from about 100 ends; among a few dozen wrong places the least bad
/// one stands out by chance (on real frames, maps of 20 to 75 frames accepted 7% to 0.03% of the
/// queries about places outside them), so with fewer rivals nothing is accepted.
constexpr int kMinRivalEnds = 100;

/// (runner_up - best) / spread; 0 when any of them is not finite, the spread is 0 or there are
/// fewer than kMinRivalEnds `rivals`.
float distinctiveness(float best, float runner_up, float spread, int rivals);

/// Sets match.accepted: a match was found and its confidence reaches `threshold`.
void applyAcceptance(Match& match, double threshold);

}  // namespace mrs_vpr
