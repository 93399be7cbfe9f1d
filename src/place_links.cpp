#include "mrs_vpr/place_links.hpp"

#include <algorithm>
#include <cstdlib>
#include <numeric>
#include <stdexcept>
#include <string>

namespace mrs_vpr {

int PlaceLinks::placeOfLocked(int frame) const {
  return frame < static_cast<int>(place_.size()) ? place_[static_cast<std::size_t>(frame)] : frame;
}

void PlaceLinks::link(int frame, int reference) {
  if (frame < 0 || reference < 0) {
    throw std::invalid_argument("a place link joins two map frames, got " + std::to_string(frame) + " and " +
                                std::to_string(reference));
  }
  std::lock_guard<std::mutex> lock(mutex_);
  const auto size = static_cast<std::size_t>(std::max(frame, reference)) + 1;
  if (place_.size() < size) {
    const auto old_size = static_cast<int>(place_.size());
    place_.resize(size);
    std::iota(place_.begin() + old_size, place_.end(), old_size);
  }
  const int a = placeOfLocked(frame);
  const int b = placeOfLocked(reference);
  if (a == b) return;
  // The older place names both: every frame of the newer one joins it.
  const int kept = std::min(a, b);
  const int joined = std::max(a, b);
  for (std::size_t i = 0; i < place_.size(); ++i) {
    if (place_[i] == joined) place_[i] = kept;
  }
  ++linked_;  // the newer place's first frame; its other frames were linked to it already
}

namespace {

/// Sorted, merged copies of `ranges`.
std::vector<FrameRange> merged(std::vector<FrameRange> ranges) {
  std::sort(ranges.begin(), ranges.end(), [](const FrameRange& a, const FrameRange& b) { return a.begin < b.begin; });
  std::vector<FrameRange> result;
  for (const FrameRange& range : ranges) {
    if (!result.empty() && range.begin <= result.back().end) {
      result.back().end = std::max(result.back().end, range.end);
    } else {
      result.push_back(range);
    }
  }
  return result;
}

bool inAny(const std::vector<FrameRange>& ranges, int value) {
  return std::any_of(ranges.begin(), ranges.end(),
                     [value](const FrameRange& range) { return value >= range.begin && value < range.end; });
}

}  // namespace

std::vector<FrameRange> PlaceLinks::samePlaceAs(int frame, int half) const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (linked_ == 0) return {};
  // The places the frames of the answer's window show, widened by `half` ...
  std::vector<FrameRange> shown;
  // ... and those of its frames linked to an older visit: the first visit's frames there are the place.
  std::vector<FrameRange> first_visit;
  for (int i = std::max(0, frame - half); i <= frame + half; ++i) {
    const int place = placeOfLocked(i);
    shown.push_back({place - half, place + half + 1});
    if (place != i) first_visit.push_back(shown.back());
  }
  shown = merged(std::move(shown));
  first_visit = merged(std::move(first_visit));
  std::vector<FrameRange> frames;
  const auto add = [&](int centre) {
    if (std::abs(centre - frame) <= half) return;  // the answer's own window
    const FrameRange range{std::max(0, centre - half), centre + half + 1};
    if (!frames.empty() && range.begin <= frames.back().end) {
      frames.back().end = std::max(frames.back().end, range.end);
    } else {
      frames.push_back(range);
    }
  };
  // Frames in ascending order, so that the ranges come sorted: a linked frame when it shows one of the
  // places, a frame of a first visit (showing itself) when it is one of them. The answer's own
  // traversal beyond its window is neither. Frames beyond the newest linked one show themselves.
  const int held = static_cast<int>(place_.size());
  // Bounds first: most frames lie far from every place (a scan of a million frames in about a millisecond).
  const int shown_begin = shown.front().begin;
  const int shown_end = shown.back().end;
  const int first_begin = first_visit.empty() ? 0 : first_visit.front().begin;
  const int first_end = first_visit.empty() ? 0 : first_visit.back().end;
  for (int i = 0; i < held; ++i) {
    const int place = place_[static_cast<std::size_t>(i)];
    const bool near = place != i ? place >= shown_begin && place < shown_end && inAny(shown, place)
                                 : i >= first_begin && i < first_end && inAny(first_visit, i);
    if (near) add(i);
  }
  for (const FrameRange& range : first_visit) {
    for (int i = std::max(held, range.begin); i < range.end; ++i) add(i);
  }
  return frames;
}

int PlaceLinks::linkedFrames() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return linked_;
}

std::size_t PlaceLinks::memoryBytes() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return place_.capacity() * sizeof(int);
}

void PlaceLinks::clear() {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<int>().swap(place_);  // its memory too
  linked_ = 0;
}

}  // namespace mrs_vpr
