#pragma once

#include <algorithm>
#include <array>
#include <cmath>
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
 * numbering's own steps, and a gap outside kStampSlack times the expected one is no loss. A stream
 * without stamps (0) or without a learnt period is judged by seq alone.
 *
 * A stream thinned on purpose is no loss either. topic_tools throttle and drop, and a driver's
 * frame-rate divider, pass their source's seq on, so every message arrives a steady step ahead (3 or
 * 4 for a 30 Hz camera throttled to 10 Hz; 1 and 2 by turns for `drop 1 3`). So each numbering learns
 * its stride, the step it usually takes: the step that three quarters of its last kStrideSteps steps
 * do not exceed. Its first kTeachingSteps steps teach it, count nothing and stand for the steps not
 * yet seen (so a burst of losses soon after them is counted); after them a step counts as loss only
 * beyond kLossStrides strides: round(step / stride) - 1 messages of the stream's own cadence. A
 * stream of every message has a stride of 1 and counts every gap, as long as fewer than a quarter of
 * its steps skip. A stream thinned from some point on is learnt within a quarter of the ring's
 * steps, each counted as loss until then.
 *
 * A node that stays slower than its camera loses messages at a steady step too: its full queue drops
 * every other one, say. So only a message that did not wait in the node's queue (the node was idle
 * when it could have come: record's `waited` false) teaches the stride: a gap before it lies
 * upstream, where a throttle thins. A message that waited is judged against the stride learnt so
 * far, or 1 before any. No ROS inside.
 */
class SequenceGaps {
 public:
  /// The most numberings followed at once; the one seen least recently makes room for a new one.
  static constexpr int kStreams = 8;
  /// The longest step a seq may take ahead of a numbering other than the newest and still continue it.
  static constexpr std::uint32_t kInterleavedStep = 1000;
  /// How far a stamp gap may lie from the seq gap times the frame period, either way, and still be loss.
  static constexpr double kStampSlack = 2.0;
  /// Recent steps of a numbering that its stride is learnt from.
  static constexpr int kStrideSteps = 16;
  /// First steps of a numbering that only teach its stride.
  static constexpr int kTeachingSteps = 2;
  /// A step of up to this many strides is the stream's own cadence (a throttle's jitter), not loss.
  static constexpr double kLossStrides = 1.5;

  /// Records the seq of a message that arrived, stamped `stamp` seconds (0: unknown); `waited` when
  /// it may have waited in the node's queue behind the message before it (the node was busy). Returns
  /// how many are missing just before it.
  std::uint64_t record(std::uint32_t seq, double stamp = 0.0, bool waited = false) {
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
    if (chosen >= 0) {
      missing = streams_[chosen].missingBefore(shortest, stamp, waited);
    } else {
      chosen = count_ < kStreams ? count_++ : leastRecent();
      streams_[chosen] = Stream{};
    }
    Stream& stream = streams_[chosen];
    stream.last_seq = seq;
    stream.seen = clock_;
    stream.last_stamp = stamp;
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
    double period = 0.0;      ///< stamp gap a seq step [s], 0 until learnt
    std::array<std::uint32_t, kStrideSteps> steps{};  ///< the latest steps forward, a ring
    int step_count = 0;

    /// The usual step: the one that three quarters of the recent steps do not exceed (so a stream
    /// that alternates steps of 1 and 2 has a stride of 2); 0 while its first steps teach it.
    std::uint32_t stride() const {
      if (step_count < kTeachingSteps) return 0;
      std::array<std::uint32_t, kStrideSteps> sorted = steps;
      constexpr int kQuantile = (3 * kStrideSteps) / 4;
      std::nth_element(sorted.begin(), sorted.begin() + kQuantile, sorted.end());
      return sorted[static_cast<std::size_t>(kQuantile)];
    }

    /// Messages missing before a step of `step` seqs forward to a message stamped `stamp`; learns
    /// the step when the message did not wait in the node's queue and, from a step of the stream's
    /// cadence, the period.
    std::uint64_t missingBefore(std::uint32_t step, double stamp, bool waited) {
      if (step == 0) return 0;  // a seq that never changes: nothing to learn from it
      const std::uint32_t learnt = stride();
      // Behind a busy node a step is judged against the upstream cadence learnt so far; before any
      // is learnt, every skipped seq is loss.
      const std::uint32_t usual = waited ? std::max<std::uint32_t>(learnt, 1) : learnt;
      const double stamp_gap = stamp - last_stamp;
      const bool stamped = stamp > 0.0 && last_stamp > 0.0;
      const bool cadence = usual == 0 || step <= kLossStrides * usual;
      std::uint64_t missing = 0;
      if (!cadence) {
        missing = static_cast<std::uint64_t>(std::llround(static_cast<double>(step) / usual)) - 1;
        if (stamped && period > 0.0) {
          const double expected = static_cast<double>(step) * period;
          if (!(stamp_gap >= expected / kStampSlack && stamp_gap <= expected * kStampSlack)) {
            missing = 0;  // another recording's numbering: start learning it afresh
            period = 0.0;
            step_count = 0;
            return missing;
          }
        }
      } else if (stamped && stamp_gap > 0.0) {
        const double per_seq = stamp_gap / step;
        period = period > 0.0 ? (1.0 - kPeriodWeight) * period + kPeriodWeight * per_seq : per_seq;
      }
      if (waited) return missing;  // its step shows the node's queue, not the stream's cadence
      // Losses count among the steps too, so that a stream thinned from now on (a throttle started
      // mid-run) is learnt within a quarter of the ring; sporadic losses leave the stride as it is.
      steps[static_cast<std::size_t>(step_count % kStrideSteps)] = step;
      ++step_count;
      if (step_count == kTeachingSteps) {
        // The teaching steps stand for the whole ring until later steps replace them, so that a
        // loss soon after them is judged against them, not against the loss itself.
        for (int i = kTeachingSteps; i < kStrideSteps; ++i) {
          steps[static_cast<std::size_t>(i)] = steps[static_cast<std::size_t>(i % kTeachingSteps)];
        }
      }
      return missing;
    }
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
