#pragma once

#include <optional>
#include <string>

#include <std_msgs/Float64MultiArray.h>

#include "mrs_vpr/LoopClosure.h"

namespace mrs_vpr {
namespace node {

/**
 * An accepted loop closure as LIO-SAM's back end (mapOptimization, loopInfoHandler) and its
 * descendants take an external one: data = [stamp of the localised test frame, stamp of the reference
 * frame], in seconds. The back end reads data[0] as the current frame and data[1] as the earlier one,
 * and looks each up among its own keyframes by time, so both must be stamps of the clock the robot's
 * other sensors use.
 *
 * Nothing for an answer that is not an accepted match (`why` stays empty), nor for a closure restated
 * for a frame its keyframe stands for (a stop; LoopClosure.localised_keyframe_stamp): the back end
 * would pair it with the keyframe it already closed, and a burst of them would push fresh closures out
 * of its short queue. Nor for an accepted one
 * with a zero stamp at either end (a test image sent unstamped, a map frame stored without a stamp):
 * the back end would read 0 as the start of its run and close a loop at the wrong keyframe. `why`
 * then says which stamp is missing.
 */
inline std::optional<std_msgs::Float64MultiArray> loopClosureStamps(const LoopClosure& closure, std::string& why) {
  if (!closure.accepted || closure.reference_index < 0 || closure.localised_keyframe_stamp != closure.header.stamp) {
    return std::nullopt;
  }
  if (closure.header.stamp.isZero()) {
    why = "the localised test frame has no stamp";
  } else if (closure.reference_stamp.isZero()) {
    why = "reference frame " + std::to_string(closure.reference_index) + " has no stamp";
  }
  if (!why.empty()) {
    return std::nullopt;
  }
  std_msgs::Float64MultiArray message;
  // Seconds as a double (steps of 0.24 us at today's Unix times) are what the convention carries.
  message.data = {closure.header.stamp.toSec(), closure.reference_stamp.toSec()};
  return message;
}

}  // namespace node
}  // namespace mrs_vpr
