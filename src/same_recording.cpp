#include "mrs_vpr/same_recording.hpp"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <functional>
#include <string_view>
#include <utility>
#include <vector>

#include "mrs_vpr/appearance_keyframes.hpp"

namespace mrs_vpr {
namespace {

std::string_view bytesOf(const DescriptorSequence& map, int frame) {
  return {reinterpret_cast<const char*>(map.view().frame(frame)), static_cast<std::size_t>(map.descriptorSize())};
}

/// A test keyframe's descriptor byte for byte among the frames near the answer, at the same stamp or
/// where either is not known (0: an unstamped replay). Generated or simulated frames without noise can
/// show one view twice on two visits, at two times.
bool holdsTwin(const DescriptorSequence& map, FrameRange test, FrameRange near) {
  const std::hash<std::string_view> hash;
  std::vector<std::pair<std::size_t, int>> test_hashes;
  for (int frame = test.begin; frame < test.end; ++frame) test_hashes.emplace_back(hash(bytesOf(map, frame)), frame);
  std::sort(test_hashes.begin(), test_hashes.end());
  for (int frame = near.begin; frame < near.end; ++frame) {
    const std::size_t key = hash(bytesOf(map, frame));
    auto same = std::lower_bound(test_hashes.begin(), test_hashes.end(), std::make_pair(key, 0));
    for (; same != test_hashes.end() && same->first == key; ++same) {
      const Stamp stamp = map.stamp(frame);
      const Stamp twin = map.stamp(same->second);
      const bool same_time = stamp == twin || stamp.isZero() || twin.isZero();
      if (same_time && bytesOf(map, frame) == bytesOf(map, same->second)) return true;
    }
  }
  return false;
}

/// A test keyframe between two consecutive map keyframes in time whose view a keyframe by it shows.
bool holdsLeftOutFrame(const DescriptorSequence& map, FrameRange test, FrameRange near, const RepeatedViews& views) {
  std::vector<std::pair<Stamp, int>> test_stamps;
  for (int frame = test.begin; frame < test.end; ++frame) {
    if (!map.stamp(frame).isZero()) test_stamps.emplace_back(map.stamp(frame), frame);
  }
  if (test_stamps.size() < 2 || !views.enabled()) return false;
  std::sort(test_stamps.begin(), test_stamps.end());
  // Two keyframes of one recording lie no farther apart than the test sequence's own keyframes span;
  // a wider gap (one session ended, another began) encloses times of other recordings.
  const std::int64_t span = test_stamps.back().first.nanoseconds() - test_stamps.front().first.nanoseconds();
  constexpr int kSide = AppearanceKeyframes::kRecentKeyframes;
  for (int frame = near.begin; frame + 1 < near.end; ++frame) {
    const Stamp from = map.stamp(frame);
    const Stamp to = map.stamp(frame + 1);
    if (from.isZero() || !(from < to) || to.nanoseconds() - from.nanoseconds() > span) continue;
    auto enclosed = std::lower_bound(test_stamps.begin(), test_stamps.end(), std::make_pair(from, 0));
    for (; enclosed != test_stamps.end() && enclosed->first < to; ++enclosed) {
      const std::uint8_t* view = map.view().frame(enclosed->second);
      for (int other = std::max(0, frame - kSide); other <= std::min(near.end - 1, frame + 1 + kSide); ++other) {
        if (views.withinNewView(map.view().frame(other), view)) return true;
      }
    }
  }
  return false;
}

}  // namespace

bool holdsOwnRecording(const DescriptorSequence& map, FrameRange test, FrameRange near, const RepeatedViews& views) {
  return holdsTwin(map, test, near) || holdsLeftOutFrame(map, test, near, views);
}

void refuseSameRecording(Match& match, const DescriptorSequence& map, FrameRange test, int searched_frames, int reach,
                         const RepeatedViews& views) {
  if (!match.accepted) return;
  const int answer = match.reference_index;
  const FrameRange near{std::max(0, answer - reach), std::min(searched_frames, answer + reach + 1)};
  if (!holdsOwnRecording(map, test, near, views)) return;
  match.same_recording = true;
  match.accepted = false;
}

}  // namespace mrs_vpr
