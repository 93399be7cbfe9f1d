#pragma once

// The options of keyframes by travel, as the node's ~min_travel, ~odom_frame and ~base_frame, which
// build_map and query_bag share.

#include <string>

#include <boost/program_options.hpp>

#include "mrs_vpr/node/bag_keyframes.hpp"

namespace mrs_vpr {
namespace tools {

/// Adds --min-travel (described by `min_travel_help`), --odom-frame and --base-frame, read into `travel`.
inline void addTravelOptions(boost::program_options::options_description& description, bag::TravelSettings& travel,
                             const std::string& min_travel_help) {
  namespace po = boost::program_options;
  // clang-format off
  description.add_options()
      ("min-travel", po::value(&travel.min_travel)->default_value(travel.min_travel), min_travel_help.c_str())
      ("odom-frame", po::value(&travel.odom_frame)->default_value(travel.odom_frame), "frame of the robot's positions")
      ("base-frame", po::value(&travel.base_frame)->default_value(travel.base_frame), "the robot's own frame");
  // clang-format on
}

}  // namespace tools
}  // namespace mrs_vpr
