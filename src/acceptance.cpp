#include "mrs_vpr/acceptance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "mrs_vpr/median.hpp"
#include "mrs_vpr/trajectory_search.hpp"

namespace mrs_vpr {

float costSpread(const std::vector<float>& costs) {
  const std::size_t step = std::max<std::size_t>(1, costs.size() / kSpreadSamples);
  std::vector<float> samples;
  samples.reserve((costs.size() + step - 1) / step);
  for (std::size_t i = 0; i < costs.size(); i += step) {
    if (std::isfinite(costs[i])) samples.push_back(costs[i]);
  }
  if (samples.size() < 3) return 0.0F;
  const float centre = upperMedian(samples);
  for (float& value : samples) value = std::abs(value - centre);
  // 1.4826 MAD is the standard deviation of a Gaussian.
  return 1.4826F * upperMedian(samples);
}

float distinctiveness(float best, float runner_up, float spread, int rivals) {
  if (!std::isfinite(best) || !std::isfinite(runner_up) || !(spread > 0.0F) || rivals < kMinRivalEnds) return 0.0F;
  return std::max(0.0F, (runner_up - best) / spread);
}

int placesAmong(int rivals, int frames_per_end, int match_exclusion) {
  return static_cast<int>(static_cast<long long>(rivals) * std::max(1, frames_per_end) /
                          std::max(1, match_exclusion / 2));
}

double requiredConfidence(int places, const SequenceParams& params) {
  if (places >= kPlacesForPlainThreshold || params.accept_threshold <= 0.0) return params.accept_threshold;
  // Fewer than 2 places cannot be told apart at all (and ln 1 = 0).
  if (places < 2) return std::numeric_limits<double>::infinity();
  return params.accept_threshold *
         std::sqrt(std::log(static_cast<double>(kPlacesForPlainThreshold)) / std::log(static_cast<double>(places)));
}

bool atVelocityBound(const Match& match, const SequenceParams& params) {
  const std::vector<double> searched = velocities(params);
  // With one or two velocities every answer is at a bound: the user has fixed the speed.
  if (searched.size() < 3 || match.reference_index < 0) return false;
  // The match's velocity is a float copy of a searched one: nearer than half a step is the same.
  const auto at = [&](double bound) { return std::abs(match.velocity - bound) < 0.5 * params.velocity_step; };
  return at(searched.front()) || at(searched.back());
}

void applyAcceptance(Match& match, const SequenceParams& params) {
  match.at_velocity_bound = atVelocityBound(match, params);
  // As among too few rivals, there is then nothing to be sure about: the gap was measured among
  // trajectories that do not fit how the robot moved.
  if (match.at_velocity_bound) match.confidence = 0.0F;
  match.accepted = match.reference_index >= 0 && match.confidence >= requiredConfidence(match.rival_places, params) &&
                   !match.at_velocity_bound;
}

std::string acceptanceVerdict(const Match& match, const SequenceParams& params) {
  if (match.reference_index < 0) return "no match found";
  if (match.accepted) return "accepted";
  if (match.rivals < kMinRivalEnds) {
    return "not accepted: the map holds " + std::to_string(match.rivals) + (match.rivals == 1 ? " end" : " ends") +
           " outside the answer's window, and the acceptance rule needs " + std::to_string(kMinRivalEnds) +
           " to tell a place from chance";
  }
  if (match.same_recording) {
    return "not accepted: the test sequence's keyframes are in the map already, at the same times with the same "
           "views (one recording added to the map twice, as a bag played again without emptying the map), and a "
           "frame that finds itself is no loop closure";
  }
  if (match.across_drives) {
    return "not accepted: the answer's trajectory runs across the junction of two drives (a map loaded and the "
           "frames added after it, or two visits appended one after the other), which is no place";
  }
  if (match.turned_back) {
    return "not accepted: the test sequence returns to a place it passed (the robot turned back or backed up), "
           "and the search's trajectories, which run forwards, do not fit the keyframe placed";
  }
  if (match.repeated_view) {
    return "not accepted: most of the test sequence's keyframes show one view again (a camera standing in a "
           "dark or textureless place, whose noise made keyframes), which says nothing about the place";
  }
  if (match.at_velocity_bound) {
    std::ostringstream message;
    message << "not accepted: the best trajectory runs at " << match.velocity
            << " map frames a frame, the slowest or fastest of sequence/velocity_min..velocity_max ("
            << params.velocity_min << ".." << params.velocity_max
            << "): the robot may be moving outside that range (another speed, a stop, backwards), or the "
               "place may not be in the map";
    return message.str();
  }
  const double required = requiredConfidence(match.rival_places, params);
  if (required > params.accept_threshold && match.confidence >= params.accept_threshold) {
    std::ostringstream message;
    message << "not accepted: confidence " << match.confidence << " below " << required
            << ", sequence/accept_threshold raised for a map of about "
            << match.rival_places << " places outside the answer's window (fewer than "
            << kPlacesForPlainThreshold << ")";
    return message.str();
  }
  return "not accepted: confidence below sequence/accept_threshold";
}

}  // namespace mrs_vpr
