#pragma once

// The options that choose keyframes as the node does (~min_travel, ~odom_frame, ~base_frame and
// ~min_appearance_change), which build_map and query_bag share.

#include <string>

#include <boost/program_options.hpp>

#include "mrs_vpr/node/bag_keyframes.hpp"
#include "double_option.hpp"

namespace mrs_vpr {
namespace tools {

/// Adds --min-travel, --odom-frame and --base-frame, read into `travel`, and --min-appearance-change,
/// read into `min_appearance_change`; the two texts describe what the first and the last mean to the tool.
/// `shown_appearance_default`, when given, is what --help shows as the last one's default (a tool
/// whose default is another program's setting), instead of its value.
inline void addKeyframingOptions(boost::program_options::options_description& description, bag::TravelSettings& travel,
                                 double& min_appearance_change, const std::string& min_travel_help,
                                 const std::string& min_appearance_change_help,
                                 const char* shown_appearance_default = nullptr) {
  namespace po = boost::program_options;
  auto* appearance = shown_appearance_default == nullptr
                         ? doubleOption(&min_appearance_change)
                         : po::value(&min_appearance_change)->default_value(min_appearance_change,
                                                                            shown_appearance_default);
  // clang-format off
  description.add_options()
      ("min-travel", po::value(&travel.min_travel)->default_value(travel.min_travel), min_travel_help.c_str())
      ("odom-frame", po::value(&travel.odom_frame)->default_value(travel.odom_frame), "frame of the robot's positions")
      ("base-frame", po::value(&travel.base_frame)->default_value(travel.base_frame), "the robot's own frame")
      ("min-appearance-change", appearance, min_appearance_change_help.c_str());
  // clang-format on
}

}  // namespace tools
}  // namespace mrs_vpr
