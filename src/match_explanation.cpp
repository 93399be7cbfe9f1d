#include "mrs_vpr/match_explanation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mrs_vpr/difference_matrix.hpp"
#include "mrs_vpr/front_end/front_end.hpp"
#include "mrs_vpr/trajectory_search.hpp"

namespace mrs_vpr {
namespace {

/// The reference frame a trajectory of `velocity` ending at `end` (at test frame `anchor`) visits at `t`:
/// the rule of the searches (trajectory_search.hpp).
int visitedFrame(int end, double velocity, int t, int anchor) {
  return end + static_cast<int>(std::lround(velocity * (t - anchor)));
}

/// Among the searched velocities, the one whose trajectory to `end` lies inside the map and has the
/// lowest mean raw difference; 0 when none fits.
double bestVelocity(SequenceView reference, SequenceView query, int end, int anchor, const SequenceParams& params) {
  double best_velocity = 0.0;
  double best_cost = std::numeric_limits<double>::infinity();
  for (const double velocity : velocities(params)) {
    const int first = visitedFrame(end, velocity, 0, anchor);
    const int last = visitedFrame(end, velocity, query.count - 1, anchor);
    if (first < 0 || last >= reference.count) continue;
    double cost = 0.0;
    for (int t = 0; t < query.count; ++t) {
      cost += descriptorDifference(query.frame(t), reference.frame(visitedFrame(end, velocity, t, anchor)),
                                   query.descriptor_size);
    }
    if (cost < best_cost) {
      best_cost = cost;
      best_velocity = velocity;
    }
  }
  return best_velocity;
}

}  // namespace

MatchExplanation explainMatch(SequenceView reference, SequenceView query, const Match& match,
                              const SequenceParams& params, const DescriptorParams& descriptor) {
  MatchExplanation explanation;
  explanation.reference_frames = reference.count;
  explanation.query_frames = query.count;
  explanation.anchor = wholeSequenceRows(query.count, params.alignment).anchor;
  if (query.count == 0) return explanation;
  const std::unique_ptr<const FrontEnd> front_end = makeFrontEnd(descriptor);
  explanation.query_thumbnail = front_end->picture(query.frame(explanation.anchor));
  const int end = match.reference_index;
  if (end < 0 || end >= reference.count) return explanation;
  explanation.reference_thumbnail = front_end->picture(reference.frame(end));

  explanation.velocity = bestVelocity(reference, query, end, explanation.anchor, params);
  int lowest = end;
  int highest = end;
  for (int t = 0; t < query.count; ++t) {
    const int frame =
        std::clamp(visitedFrame(end, explanation.velocity, t, explanation.anchor), 0, reference.count - 1);
    explanation.trajectory.push_back(frame);
    lowest = std::min(lowest, frame);
    highest = std::max(highest, frame);
  }

  // A margin of a quarter of the trajectory's span on either side shows whether the match stands out.
  const int margin = std::max(10, (highest - lowest) / 4);
  const int last = std::min(reference.count - 1, highest + margin);
  const int side = std::max(query.count, last - std::max(0, lowest - margin) + 1);
  const int step = (side + kMaxBandSide - 1) / kMaxBandSide;
  // Both grids pass through the answer (anchor row, answer column), so that a trajectory of
  // velocity 1 visits sampled cells only: on a grid not aligned with it, most of its cells would fall
  // between the samples and the matching stretch would not show.
  const int first = end - (end - std::max(0, lowest - margin)) / step * step;
  explanation.band_first = first;
  explanation.band_first_row = explanation.anchor % step;
  explanation.band_step = step;
  explanation.band = computeDifferenceMatrix(query.subsample(explanation.band_first_row, step),
                                             reference.slice(first, last + 1).subsample(0, step));
  return explanation;
}

}  // namespace mrs_vpr
