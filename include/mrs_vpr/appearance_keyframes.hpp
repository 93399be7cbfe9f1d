#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "mrs_vpr/descriptor_regions.hpp"
#include "mrs_vpr/parameters.hpp"

namespace mrs_vpr {

/**
 * Keyframes chosen by how much the view has changed, for a camera without odometry: a frame becomes a
 * keyframe once it differs from the frames seen since the last keyframe by `min_change` times the
 * difference between unrelated views. A robot that stands still adds no keyframe, and a slow one adds
 * fewer than a fast one, so that a sequence of keyframes covers about the same stretch of the world
 * whatever the robot's speed.
 *
 * - The change is measured against the mean descriptor of the keyframe and of the frames since that
 *   lie within kReferenceShare of `min_change` of the keyframe itself, so that sensor noise averages
 *   out of the reference while a robot stands. Those frames are measured against the keyframe, not
 *   against the mean, so that a view drifting away on slow smooth motion cannot drag the reference
 *   along step by step (which would hold the change below `min_change` for many places): the reference
 *   stays within kReferenceShare of the keyframe.
 * - Descriptors are compared region by region (HOG's blocks, the thumbnail's patches) and the median
 *   region's mean absolute difference is taken: a passer-by, or noise that block normalisation
 *   amplifies in a textureless patch such as the sky, changes a few regions, not the median one.
 * - A view seen among this traversal's last kRecentKeyframes keyframes is not new: the frame must
 *   differ by `min_change` from each of them too. In a textureless view the noise of a standing
 *   camera can exceed `min_change` against the newest keyframe, and every such frame would become a
 *   keyframe; against a dozen noisy copies of the same view one of them lies closer. On the real-data
 *   benchmark's camera drives (tune half, 30 seeds) keyframes in stops fell from 720 to 294 on the
 *   revisits and from 1922 to 549 on the map drives; moving keyframes fell by under 1%.
 *   A follower() leaves this out: it measures another camera's views on the map's scale, which can
 *   exceed what that camera's views differ by at all (blur, fog, night), and then a moving camera's
 *   older keyframes lie within the threshold too (the generated route's darker, blurred traversal
 *   kept 80 keyframes of 332 frames with it, 138 without).
 * - A standing camera's frame like one that joined the reference is not new either. Its noise,
 *   vibration and passer-by lift a frame now and then over `min_change` from the reference (0.5 to 1.1
 *   of it), but seldom from every one of the last kJoinedFrames noisy copies of the view that joined
 *   it. Such a stray keyframe repeats the view within every test sequence that holds it, and those fit
 *   no constant speed. Only frames within kStrayShare of `min_change` of the keyframe are compared:
 *   a frame farther away is motion, and a slowly drifting view would otherwise stay near its own
 *   latest joined frame (on the generated route, 126 frames without a keyframe at 1.5).
 * - The scale is the data's own: the median change between keyframes kUnrelatedGap keyframes apart,
 *   over the last kScaleSamples such pairs. Until kMinScaleSamples pairs exist, the change from a view
 *   of noise (unrelated to any place by construction) stands in for it, so that a robot standing still
 *   from the start adds no keyframe either. It stands in as well while that median is 0 (most pairs
 *   one view: keyframes of a covered camera taken by travel, or loaded so). A frame is compared with
 *   an older recent keyframe on the smaller of the two stand-ins, the reference's and that keyframe's:
 *   a reference without the structure of a place (a black, saturated or nearly uniform frame of a
 *   camera starting up, an exposure glitch, a covered lens, a smooth gradient, a text overlay on
 *   black; HOG is then zero or one orientation) lies farther from noise than any place does, and on
 *   its stand-in every later frame looked like an older keyframe's view (Nordland summer: one black
 *   keyframe after 21 left the next 150 frames without a keyframe).
 *
 * No ROS inside; not thread-safe (one owner, one frame at a time).
 */
class AppearanceKeyframes {
 public:
  /// Keyframes apart whose views are taken as unrelated places.
  static constexpr int kUnrelatedGap = 50;
  /// Pairs the scale is the median of.
  static constexpr int kScaleSamples = 101;
  /// Pairs needed before the scale replaces the stand-in.
  static constexpr int kMinScaleSamples = 9;
  /// This traversal's keyframes a new keyframe must differ from (tried on the tune half: 4, 8, 16).
  static constexpr int kRecentKeyframes = 16;
  static_assert(kRecentKeyframes <= kUnrelatedGap, "the recent keyframes are read from those the scale keeps");
  /// Frames that joined the reference a frame is compared with, the newest first.
  static constexpr int kJoinedFrames = 8;
  /// Frames beyond this share of `min_change` from the keyframe are not compared with the joined ones:
  /// a standing camera's frames lie within 1.1 of it on the real-data benchmark's camera drives.
  /// Chosen on the tune half's drives (doc/keyframes.md); 1.5 breaks slow, smooth motion.
  static constexpr double kStrayShare = 1.25;
  /// A skipped frame joins the reference when it lies within this share of `min_change` of the
  /// keyframe. A standing camera's frames differ from its keyframe by 0.5 to 1.1 of `min_change` on the
  /// real-data benchmark's camera drives (noise that block normalisation amplifies, gain, a passer-by),
  /// so at half of it few would join and the noise would not average out. Chosen on the tune half
  /// (0.75 and 0.9 tried): doc/keyframes.md. Near 1 the reference follows slow motion again (1.0 left 130
  /// frames between two keyframes of the generated route).
  static constexpr double kReferenceShare = 0.75;
  /// Seed of the noise image whose view stands in for an unrelated one.
  static constexpr std::uint64_t kNoiseSeed = 1;

  /// Keyframes of descriptors of `front_end`; `min_change` 0 (or less) makes every frame a keyframe.
  /// Throws std::invalid_argument when the front end's parameters are invalid.
  AppearanceKeyframes(const DescriptorParams& front_end, double min_change);

  bool enabled() const { return min_change_ > 0.0; }
  /// The change that makes a keyframe, in units of scale().
  double minChange() const { return min_change_; }
  /// True when `descriptor` has changed enough since the last keyframe (always for the first frame, and
  /// when disabled). Does not remember it: call keep() or skip().
  bool wants(const cv::Mat& descriptor);
  /// Records a keyframe.
  void keep(const cv::Mat& descriptor);
  /// wants(), then keep() or skip() as it says: true when `descriptor` became a keyframe.
  bool offer(const cv::Mat& descriptor);
  /// Records a frame that was not kept: it joins the mean the next frames are compared with when it
  /// lies within kReferenceShare of `min_change` of the keyframe.
  void skip(const cv::Mat& descriptor);
  /// Forgets the last keyframe and the scale (after the map is reset).
  void reset();
  /// Keyframes of another traversal by the same camera (a test sequence): no last keyframe yet, but the
  /// scale learnt here, which goes on from there.
  AppearanceKeyframes follower() const;

  /// Whether wants() last refused a frame because it looks like one of the older recent keyframes
  /// (kRecentKeyframes), not like the newest: a view seen again, which the newest keyframe does not
  /// stand for.
  bool lastSeenBefore() const { return last_seen_before_; }
  /// Whether the frame wants() last looked at lies within kReferenceShare of `min_change` of the
  /// reference: the newest keyframe's own view, for which that keyframe's closure holds. A frame
  /// between that and `min_change` is too similar to be a keyframe but may be on its way to the next
  /// place (a slow or creeping camera).
  bool lastStood() const { return last_change_ < kReferenceShare * min_change_; }
  /// The change of the frame wants() last looked at, in units of the scale (0 before any).
  double lastChange() const { return last_change_; }
  /// The difference between unrelated views the change is measured in (bytes, mean absolute).
  double scale() const;

  /// The median over regions of the mean absolute difference of `a` and `b` (descriptorSize() bytes).
  double regionDifference(const std::uint8_t* a, const float* b) const;
  /// The regions the differences are measured over (shared by every copy).
  const std::shared_ptr<const DescriptorRegions>& regions() const { return regions_; }

 private:
  /// The change from the view of noise to `view`: what stands in for the scale (see the class).
  double standIn(const float* view) const;
  /// The data's own scale, once kMinScaleSamples pairs give one above 0.
  std::optional<double> learntScale() const;
  /// The reference the change is measured from: the mean of the keyframe and the frames that joined it.
  std::vector<float> referenceMean() const;

  double min_change_;
  int size_;
  std::shared_ptr<const DescriptorRegions> regions_;
  std::vector<std::uint8_t> unrelated_view_;  ///< The descriptor of seeded noise, the scale's stand-in.
  /// Sum of the descriptors since the last keyframe (whole numbers, exact in a double for any stop) ...
  std::vector<double> sum_;
  int frames_in_mean_ = 0;  ///< ... and how many there are.
  std::deque<std::vector<float>> recent_keyframes_;  ///< The last kUnrelatedGap keyframes.
  std::deque<double> keyframe_stand_ins_;  ///< standIn() of each of recent_keyframes_.
  /// False for a follower (see kRecentKeyframes), whose recent_keyframes_ start with the map's.
  bool compare_recent_ = true;
  std::deque<std::vector<float>> joined_;  ///< The last kJoinedFrames frames that joined the reference.
  std::deque<double> samples_;       ///< Differences of keyframes kUnrelatedGap apart.
  double last_change_ = 0.0;
  double last_keyframe_change_ = 0.0;  ///< The last frame's change from the keyframe itself.
  bool last_seen_before_ = false;
};

}  // namespace mrs_vpr
