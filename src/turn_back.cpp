#include "mrs_vpr/turn_back.hpp"

#include <algorithm>
#include <vector>

#include "mrs_vpr/appearance_keyframes.hpp"

namespace mrs_vpr {

bool returnsToPassedPlace(const DescriptorSequence& map, FrameRange test, int localised_row,
                          const RepeatedViews& views) {
  const int first = test.begin + std::max(localised_row, 0);
  if (!views.enabled() || first >= test.end) return false;
  constexpr int kRecent = AppearanceKeyframes::kRecentKeyframes;
  const SequenceView frames = map.view();
  const int earliest = std::max(0, test.begin - test.size() - kRecent);
  // The newest passed keyframe that `keyframe` shows again, or -1.
  const auto passedPlace = [&](int keyframe) {
    for (int passed = keyframe - kRecent - 1; passed >= earliest; --passed) {
      if (views.withinNewView(frames.frame(passed), frames.frame(keyframe))) return passed;
    }
    return -1;
  };
  const int step = (test.size() + RepeatedViews::kMaxJudged - 1) / RepeatedViews::kMaxJudged;
  int judged_after = 0;      // judged keyframes from the localised one on ...
  int returning_after = 0;   // ... and those of them that return
  std::vector<int> places;   // the passed keyframe each returning keyframe shows, oldest test keyframe first
  for (int keyframe = test.begin; keyframe < test.end; keyframe += step) {
    const int place = passedPlace(keyframe);
    if (keyframe >= first) ++judged_after;
    if (place < 0) continue;
    places.push_back(place);
    if (keyframe >= first) ++returning_after;
  }
  if (2 * returning_after <= judged_after) return false;
  // A robot going round a small loop returns too, but forwards: the places it shows again follow on.
  return places.size() < 2 || places.back() < places.front();
}

void refuseTurnsBack(Match& match, const DescriptorSequence& map, FrameRange test, int localised_row,
                     const RepeatedViews& views) {
  if (!match.accepted || !returnsToPassedPlace(map, test, localised_row, views)) return;
  match.turned_back = true;
  match.accepted = false;
}

}  // namespace mrs_vpr
