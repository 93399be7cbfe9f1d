#include "mrs_vpr/turn_back.hpp"

#include <algorithm>
#include <cstddef>
#include <vector>

#include "mrs_vpr/appearance_keyframes.hpp"

namespace mrs_vpr {

bool returnsToPassedPlace(const DescriptorSequence& map, FrameRange test, int localised_row, int unsearched,
                          const RepeatedViews& views) {
  const int first = test.begin + std::max(localised_row, 0);
  if (!views.enabled() || first >= test.end) return false;
  constexpr int kRecent = AppearanceKeyframes::kRecentKeyframes;
  const SequenceView frames = map.view();
  const int earliest = std::max(0, test.begin - std::max(test.size() + kRecent, unsearched));
  // The oldest passed keyframe within reach that `keyframe` shows again, or -1: after a robot backed up
  // and drives on, the way out's keyframe, not the way back's, tells which way it goes.
  const auto passedPlace = [&](int keyframe) {
    for (int passed = earliest; passed < keyframe - kRecent; ++passed) {
      if (views.withinNewView(frames.frame(passed), frames.frame(keyframe))) return passed;
    }
    return -1;
  };
  const int step = (test.size() + RepeatedViews::kMaxJudged - 1) / RepeatedViews::kMaxJudged;
  std::vector<int> judged;  // the keyframes judged, oldest first ...
  for (int keyframe = test.begin; keyframe < test.end; keyframe += step) judged.push_back(keyframe);
  std::vector<int> places(judged.size(), -1);  // ... and the place each returns to
  const auto from_localised = static_cast<std::size_t>(
      std::lower_bound(judged.begin(), judged.end(), first) - judged.begin());
  // Most keyframes from the localised one on must return; in a forward drive a few that do not decide.
  const int after = static_cast<int>(judged.size() - from_localised);
  if (after == 0) return false;
  int staying = 0;  // judged keyframes from the localised one on that do not return
  for (std::size_t i = from_localised; i < judged.size(); ++i) {
    places[i] = passedPlace(judged[i]);
    if (places[i] < 0 && 2 * ++staying >= after) return false;
  }
  for (std::size_t i = 0; i < from_localised; ++i) places[i] = passedPlace(judged[i]);
  int onwards = 0;  // returning keyframes that show a place passed after the previous one's ...
  int backwards = 0;  // ... and before it
  int last_place = -1;
  for (int place : places) {
    if (place < 0) continue;
    if (last_place >= 0 && place != last_place) ++(place > last_place ? onwards : backwards);
    last_place = place;
  }
  // A robot going round a small loop returns too, but onwards. A keyframe returning alone gives no
  // direction; it is taken as a turn just begun (with the causal alignment, the newest keyframe only).
  return onwards <= backwards;
}

void refuseTurnsBack(Match& match, const DescriptorSequence& map, FrameRange test, int localised_row, int unsearched,
                     const RepeatedViews& views) {
  if (!match.accepted || !returnsToPassedPlace(map, test, localised_row, unsearched, views)) return;
  match.turned_back = true;
  match.accepted = false;
}

}  // namespace mrs_vpr
