#pragma once

#include <cstdint>

namespace mrs_vpr {
namespace node {

/**
 * Counts the messages of a stream that never arrived, by the gaps in their header.seq. roscpp and
 * rospy number each publisher's messages 0, 1, 2, ...; a message lost on the way (a full subscriber
 * queue, ~image_queue_size, while large frames take long to describe; a publisher that could not send)
 * leaves a gap, and nothing else tells the subscriber about it. A seq that does not move forward (a
 * new publisher, a bag played again, messages passed within a nodelet manager, which keep the seq
 * their sender set) restarts the count without a gap. Seqs are compared as 32-bit serial numbers
 * (RFC 1982): 4294967295 is just before 0, so a counter that wraps around loses nothing, and a jump
 * back that wraps below 0 (4001, then 4294967295) is a restarted sender, not 4.29 billion lost
 * frames. No ROS inside.
 */
class SequenceGaps {
 public:
  /// Records the seq of a message that arrived; returns how many are missing just before it.
  std::uint64_t record(std::uint32_t seq) {
    // The distance forward modulo 2^32: a step of 2^31 or more forward is a step backward.
    const std::uint32_t step = seq - last_seq_;
    const bool forward = has_seq_ && step != 0 && step < 0x80000000U;
    const std::uint64_t missing = forward ? step - 1 : 0;
    has_seq_ = true;
    last_seq_ = seq;
    return missing;
  }

 private:
  bool has_seq_ = false;
  std::uint32_t last_seq_ = 0;
};

}  // namespace node
}  // namespace mrs_vpr
