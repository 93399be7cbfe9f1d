#pragma once

#include <array>
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
 * frames.
 *
 * Two publishers at once (a bag played while the camera runs) interleave two numberings, and image
 * callbacks do not say which publisher sent a message. So a few numberings are followed, and each seq
 * continues the one it is the shortest step ahead of; a step of more than kInterleavedStep ahead of
 * one that is not the newest is a numbering of its own. Only the first jump from one numbering to
 * the other, which nothing yet tells from a gap, is counted.
 *
 * A jump forward that the stamps do not bear out is a numbering of its own too: one recording played
 * after another (seq 1599, then 5000, stamps a day apart), or a camera driver restarted. Lost frames
 * leave a stamp gap of about as many frame periods as the seq gap; the period is learnt from the
 * numbering's own steps of one, and a gap outside kStampSlack times the expected one is no loss. A
 * stream without stamps (0) or without a learnt period is judged by seq alone. No ROS inside.
 */
class SequenceGaps {
 public:
  /// The most numberings followed at once; the one seen least recently makes room for a new one.
  static constexpr int kStreams = 8;
  /// The longest step a seq may take ahead of a numbering other than the newest and still continue it.
  static constexpr std::uint32_t kInterleavedStep = 1000;
  /// How far a stamp gap may lie from the seq gap times the frame period, either way, and still be loss.
  static constexpr double kStampSlack = 2.0;

  /// Records the seq of a message that arrived, stamped `stamp` seconds (0: unknown); returns how many
  /// are missing just before it.
  std::uint64_t record(std::uint32_t seq, double stamp = 0.0) {
    ++clock_;
    int chosen = -1;
    std::uint32_t shortest = 0;
    for (int i = 0; i < count_; ++i) {
      // The distance forward modulo 2^32: a step of 2^31 or more forward is a step backward.
      const std::uint32_t step = seq - streams_[i].last_seq;
      const bool forward = step < 0x80000000U;
      if (!forward || (i != newest_ && step > kInterleavedStep)) continue;
      if (chosen < 0 || step < shortest) {
        chosen = i;
        shortest = step;
      }
    }
    std::uint64_t missing = 0;
    double period = 0.0;
    if (chosen >= 0) {
      Stream& stream = streams_[chosen];
      period = stream.period;
      const double stamp_gap = stamp - stream.last_stamp;
      const bool stamped = stamp > 0.0 && stream.last_stamp > 0.0;
      if (shortest == 1 && stamped && stamp_gap > 0.0) {
        period = period > 0.0 ? (1.0 - kPeriodWeight) * period + kPeriodWeight * stamp_gap : stamp_gap;
      }
      missing = shortest == 0 ? 0 : shortest - 1;
      if (missing > 0 && stamped && period > 0.0) {
        const double expected = static_cast<double>(shortest) * period;
        if (!(stamp_gap >= expected / kStampSlack && stamp_gap <= expected * kStampSlack)) {
          missing = 0;  // another recording's numbering
          period = 0.0;
        }
      }
    } else {
      chosen = count_ < kStreams ? count_++ : leastRecent();
    }
    streams_[chosen] = {seq, clock_, stamp, period};
    newest_ = chosen;
    return missing;
  }

 private:
  /// Weight of the newest step in the learnt frame period.
  static constexpr double kPeriodWeight = 0.1;

  struct Stream {
    std::uint32_t last_seq = 0;
    std::uint64_t seen = 0;   ///< clock_ when its last seq came
    double last_stamp = 0.0;  ///< [s], 0 when unknown
    double period = 0.0;      ///< between messages one seq apart [s], 0 until learnt
  };

  int leastRecent() const {
    int oldest = 0;
    for (int i = 1; i < count_; ++i) {
      if (streams_[i].seen < streams_[oldest].seen) oldest = i;
    }
    return oldest;
  }

  std::array<Stream, kStreams> streams_{};
  int count_ = 0;
  int newest_ = -1;
  std::uint64_t clock_ = 0;
};

}  // namespace node
}  // namespace mrs_vpr
