#pragma once

#include <algorithm>
#include <cstdint>
#include <memory>

#include "mrs_vpr/appearance_keyframes.hpp"
#include "mrs_vpr/descriptor_regions.hpp"
#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/match.hpp"

namespace mrs_vpr {

/**
 * Whether most keyframes of a test sequence show a view that the sequence shows again further on: a
 * camera standing in a dark or textureless place, whose noise block normalisation amplifies until
 * frame after frame passes `min_appearance_change`, makes such keyframes. A sequence of one view
 * carries no sequence to match, and two such stops, in two dark places, look alike: on the real-data
 * benchmark's camera drives a stop in a tunnel was accepted as a loop closure to another tunnel stop
 * up to 19 times a drive. An answer about such a sequence is not accepted (Match::repeated_view).
 *
 * A keyframe repeats a view when another keyframe of the sequence, kMinGap to kRecentKeyframes
 * keyframes away, differs from it by less than AppearanceKeyframes::kStrayShare of
 * `min_appearance_change`: what noisy copies of one view differ by, while keyframes of a moving camera
 * a few keyframes apart show different places. Neighbours closer than kMinGap are not compared: a slow
 * camera's consecutive keyframes lie that close. Long sequences are judged on kMaxJudged keyframes
 * spread over them.
 *
 * The distances are on the scale of the map's camera, so the rule judges only test sequences of the
 * map's own keyframes (PlaceRecognizer::matchRecent: the node's continuous mode and `recent_frames`
 * queries). Another camera's traversal can differ less on that scale than the map's camera does
 * between places (blur, fog, night: AppearanceKeyframes::follower), and its moving keyframes would
 * then count as repeats: judged so, the per-frame evaluation of the generated route's camera drives
 * (test/tools/make_drive_test.cpp) accepted no answer at all.
 */
class RepeatedViews {
 public:
  /// Keyframes apart, at least, for two keyframes to count as one view shown again.
  static constexpr int kMinGap = 3;
  /// Keyframes judged at most; longer sequences are sampled evenly.
  static constexpr int kMaxJudged = 64;
  /// Every how many keyframes of a sequence of `keyframes` one is judged, so that at most kMaxJudged are.
  static constexpr int judgingStride(int keyframes) { return std::max(1, (keyframes + kMaxJudged - 1) / kMaxJudged); }

  /// Judged on the regions and the scale of `keyframes` as they are now.
  explicit RepeatedViews(const AppearanceKeyframes& keyframes);

  /// Whether the rule can judge: keyframes by appearance are on and their scale is known.
  bool enabled() const { return same_view_ > 0.0; }
  /// Whether more than half the judged keyframes of `sequence` repeat a view.
  bool mostlyRepeated(SequenceView sequence) const;
  /// Whether two descriptors differ by less than `min_appearance_change`: a frame like `b` would not
  /// have become a keyframe after `a`. False while the rule cannot judge.
  bool withinNewView(const std::uint8_t* a, const std::uint8_t* b) const {
    return enabled() && regions_->difference(a, b) < new_view_;
  }

 private:
  std::shared_ptr<const DescriptorRegions> regions_;
  /// Region difference below which two keyframes show one view (bytes); 0 when the rule is off.
  double same_view_ = 0.0;
  /// Region difference below which a frame is no new keyframe: `min_appearance_change` on the scale.
  double new_view_ = 0.0;
};

/// Takes back the acceptance of `match` when its test sequence mostly repeats a view, and says so
/// (Match::repeated_view). Judges only accepted answers: the pass over the keyframes changes nothing else.
void refuseRepeatedViews(Match& match, SequenceView test_sequence, const RepeatedViews& views);

}  // namespace mrs_vpr
