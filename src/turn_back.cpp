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
  const int within_sequence = test.size() + kRecent;
  const int reach = std::max(within_sequence, std::min(unsearched, kReachInSequenceLengths * within_sequence));
  const int earliest = std::max(0, test.begin - reach);
  // The oldest passed keyframe within reach that `keyframe` shows again, or -1: after a robot backed up
  // and drives on, the way out's keyframe, not the way back's, tells which way it goes.
  const auto passedPlace = [&](int keyframe) {
    for (int passed = earliest; passed < keyframe - kRecent; ++passed) {
      if (views.withinNewView(frames.frame(passed), frames.frame(keyframe))) return passed;
    }
    return -1;
  };
  const int step = RepeatedViews::judgingStride(test.size());
  std::vector<int> judged;  // the keyframes judged, oldest first, the localised one among them ...
  for (int keyframe = test.begin + (first - test.begin) % step; keyframe < test.end; keyframe += step) {
    judged.push_back(keyframe);
  }
  std::vector<int> places(judged.size(), -1);  // ... and the place each returns to
  const auto localised = static_cast<std::size_t>((first - judged.front()) / step);
  // Most keyframes from the localised one on must return; in a forward drive a few that do not decide.
  const int after = static_cast<int>(judged.size() - localised);
  int staying = 0;  // judged keyframes from the localised one on that do not return
  for (std::size_t i = localised; i < judged.size(); ++i) {
    places[i] = passedPlace(judged[i]);
    if (places[i] < 0 && 2 * ++staying >= after) return false;
  }
  // The localised keyframe must lie where the robot went back: judged by the returning keyframes next
  // to it (itself among them when it returns, else it lies between them). A keyframe of the way out
  // before the turn is the way out's answer, and one of a way forward again after backing up (a
  // zig-zag) too.
  int previous = -1;
  for (std::size_t i = localised; i-- > 0 && previous < 0;) previous = passedPlace(judged[i]);
  int next = -1;
  for (std::size_t i = localised + 1; i < judged.size() && next < 0; ++i) next = places[i];
  const int place = places[localised];
  if (place < 0) return previous >= 0 && next >= 0 && next < previous;
  // Alone, it gives no direction; it is taken as a turn just begun (with the causal alignment, the
  // newest keyframe only).
  if (previous < 0 && next < 0) return true;
  return previous > place || (next >= 0 && next < place);
}

void refuseTurnsBack(Match& match, const DescriptorSequence& map, FrameRange test, int localised_row, int unsearched,
                     const RepeatedViews& views) {
  if (!match.accepted || !returnsToPassedPlace(map, test, localised_row, unsearched, views)) return;
  match.turned_back = true;
  match.accepted = false;
}

}  // namespace mrs_vpr
