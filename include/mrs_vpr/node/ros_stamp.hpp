#pragma once

#include <ros/time.h>

#include "mrs_vpr/stamp.hpp"

namespace mrs_vpr {
namespace node {

/// The exact stamp of a ROS time (never through a double). Throws std::invalid_argument only for an
/// unnormalised time (nsec >= 10^9, as a message may carry) whose sum lies beyond Stamp's range.
inline Stamp stampOf(const ros::Time& time) { return Stamp::fromSecondsAndNanoseconds(time.sec, time.nsec); }

/// The ROS time of a stamp: exact, and never out of range, as a Stamp spans exactly ROS's times.
inline ros::Time rosTimeOf(Stamp stamp) { return ros::Time(stamp.wholeSeconds(), stamp.nanosecondsOfSecond()); }

}  // namespace node
}  // namespace mrs_vpr
