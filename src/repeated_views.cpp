#include "mrs_vpr/repeated_views.hpp"

#include <algorithm>
#include <vector>

namespace mrs_vpr {

RepeatedViews::RepeatedViews(const AppearanceKeyframes& keyframes) : regions_(keyframes.regions()) {
  if (keyframes.enabled()) {
    new_view_ = keyframes.minChange() * keyframes.scale();
    same_view_ = AppearanceKeyframes::kStrayShare * new_view_;
  }
}

bool RepeatedViews::mostlyRepeated(SequenceView sequence) const {
  if (!enabled() || sequence.count <= kMinGap) return false;
  const int step = judgingStride(sequence.count);
  int judged_count = 0;
  int repeats = 0;
  const int to_judge = (sequence.count + step - 1) / step;
  for (int i = 0; i < sequence.count; i += step) {
    // Decided once either side holds more than half.
    if (2 * repeats > to_judge || 2 * (judged_count - repeats) >= to_judge) break;
    ++judged_count;
    const auto shows_it = [&](int j) {
      return j >= 0 && j < sequence.count &&
             regions_->difference(sequence.frame(j), sequence.frame(i)) < same_view_;
    };
    for (int gap = kMinGap; gap <= AppearanceKeyframes::kRecentKeyframes; ++gap) {
      if (shows_it(i - gap) || shows_it(i + gap)) {
        ++repeats;
        break;
      }
    }
  }
  return 2 * repeats > to_judge;
}

void refuseRepeatedViews(Match& match, SequenceView test_sequence, const RepeatedViews& views) {
  if (!match.accepted || !views.mostlyRepeated(test_sequence)) return;
  match.repeated_view = true;
  match.accepted = false;
}

}  // namespace mrs_vpr
