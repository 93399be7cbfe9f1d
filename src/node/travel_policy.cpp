#include "mrs_vpr/node/travel_policy.hpp"

namespace mrs_vpr {
namespace node {

TravelPolicy::TravelPolicy(double min_travel) : min_travel_(min_travel) {}

bool TravelPolicy::wants(const Eigen::Vector3d& position) const {
  return !enabled() || !has_keyframe_ || (position - last_position_).norm() >= min_travel_;
}

void TravelPolicy::keep(const Eigen::Vector3d& position) {
  has_keyframe_ = true;
  last_position_ = position;
}

void TravelPolicy::reset() { has_keyframe_ = false; }

}  // namespace node
}  // namespace mrs_vpr
