#include "mrs_vpr/place_links.hpp"

#include <algorithm>
#include <cstdlib>
#include <iterator>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

namespace mrs_vpr {
namespace {

/// Frames whose place is an older frame's, of `place` as placesOf() gives it.
int framesLinked(const std::vector<int>& place) {
  int linked = 0;
  for (std::size_t i = 0; i < place.size(); ++i) linked += place[i] != static_cast<int>(i) ? 1 : 0;
  return linked;
}

}  // namespace

int PlaceLinks::placeOfLocked(int frame) const {
  return frame < static_cast<int>(place_.size()) ? place_[static_cast<std::size_t>(frame)] : frame;
}

bool PlaceLinks::link(int frame, int reference) {
  if (frame < 0 || reference < 0) {
    throw std::invalid_argument("a place link joins two map frames, got " + std::to_string(frame) + " and " +
                                std::to_string(reference));
  }
  std::lock_guard<std::mutex> lock(mutex_);
  const auto size = static_cast<std::size_t>(std::max(frame, reference)) + 1;
  const auto old_size = static_cast<int>(place_.size());
  if (place_.size() < size) {
    place_.resize(size);
    std::iota(place_.begin() + old_size, place_.end(), old_size);
  }
  const int a = placeOfLocked(frame);
  const int b = placeOfLocked(reference);
  if (a == b) return false;
  // Before the change, so that a failure for want of memory changes nothing.
  if (made_.size() == made_.capacity()) made_.reserve(std::max<std::size_t>(64, 2 * made_.size()));
  if (keep_unsaved_) unsaved_.push_back({frame, reference});
  made_.push_back({frame, reference});
  // The older place names both: every frame of the newer one joins it.
  const int kept = std::min(a, b);
  const int joined = std::max(a, b);
  if (joined >= old_size) {
    // A frame linked for the first time (continuous mode's newest keyframes): no other shows its place.
    place_[static_cast<std::size_t>(joined)] = kept;
  } else {
    for (std::size_t i = 0; i < place_.size(); ++i) {
      if (place_[i] == joined) place_[i] = kept;
    }
  }
  ++linked_;  // the newer place's first frame; its other frames were linked to it already
  return true;
}

std::vector<FrameRange> PlaceLinks::samePlaceAs(int frame, int half) const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (linked_ == 0) return {};
  // The places the frames of the answer's window show, runs of them apart by at most `half` joined.
  std::vector<FrameRange> shown;
  for (int i = std::max(0, frame - half); i <= frame + half; ++i) {
    const int place = placeOfLocked(i);
    shown.push_back({place, place + half + 1});
  }
  shown = mergedRanges(std::move(shown));
  for (FrameRange& range : shown) range.end -= half;
  const auto showsThePlace = [&](int place) {
    return std::any_of(shown.begin(), shown.end(),
                       [place](const FrameRange& range) { return place >= range.begin && place < range.end; });
  };
  // Every other visit's frames that show one of those places, in runs apart by at most `half`: the
  // first visit's frames there (they show themselves) and every frame linked to one of them. Frames
  // beyond the newest linked one show themselves. The answer's own window is its own.
  std::vector<FrameRange> runs;
  const auto add = [&](int i) {
    if (std::abs(i - frame) <= half) return;
    if (!runs.empty() && i <= runs.back().end + half) {
      runs.back().end = i + 1;
    } else {
      runs.push_back({i, i + 1});
    }
  };
  const int held = static_cast<int>(place_.size());
  const int lowest = shown.front().begin;  // bounds first: most frames show none (1 ms a million frames)
  const int highest = shown.back().end;
  for (int i = 0; i < held; ++i) {
    const int place = place_[static_cast<std::size_t>(i)];
    if (place >= lowest && place < highest && showsThePlace(place)) add(i);
  }
  for (const FrameRange& range : shown) {
    for (int i = std::max(held, range.begin); i < range.end; ++i) add(i);
  }
  // Each run is that visit's window at the place: as wide as the answer's own at least, where its
  // frames are few (where few of its keyframes were linked).
  for (FrameRange& run : runs) {
    const int centre = (run.begin + run.end - 1) / 2;
    run = {std::max(0, std::min(run.begin, centre - half)), std::max(run.end, centre + half + 1)};
  }
  return mergedRanges(std::move(runs));
}

int PlaceLinks::linkedFrames() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return linked_;
}

std::size_t PlaceLinks::memoryBytes() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return place_.capacity() * sizeof(int) + made_.capacity() * sizeof(PlaceLink);
}

void PlaceLinks::clear() {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<int>().swap(place_);  // its memory too
  std::vector<PlaceLink>().swap(made_);
  linked_ = 0;
  std::vector<PlaceLink>().swap(unsaved_);
}

std::vector<int> PlaceLinks::placesOf(const std::vector<PlaceLink>& links, int frames) {
  int held = 0;
  for (const PlaceLink& link : links) {
    if (link.frame < 0 || link.reference < 0 || link.frame >= frames || link.reference >= frames) {
      throw std::invalid_argument("a place link joins frames " + std::to_string(link.frame) + " and " +
                                  std::to_string(link.reference) + ", outside a map of " + std::to_string(frames) +
                                  " frames");
    }
    held = std::max({held, link.frame + 1, link.reference + 1});
  }
  // Union-find whose root is always its set's oldest frame, the name link() gives a place.
  std::vector<int> place(static_cast<std::size_t>(held));
  std::iota(place.begin(), place.end(), 0);
  const auto root = [&place](int frame) {
    while (place[static_cast<std::size_t>(frame)] != frame) {
      auto& parent = place[static_cast<std::size_t>(frame)];
      parent = place[static_cast<std::size_t>(parent)];  // path halving
      frame = parent;
    }
    return frame;
  };
  for (const PlaceLink& link : links) {
    const int a = root(link.frame);
    const int b = root(link.reference);
    place[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
  }
  // A frame's parent is older than it, so in increasing order each parent is already its root.
  for (std::size_t i = 0; i < place.size(); ++i) place[i] = place[static_cast<std::size_t>(place[i])];
  return place;
}

void PlaceLinks::adopt(std::vector<int>&& places, std::vector<PlaceLink>&& links) noexcept {
  std::lock_guard<std::mutex> lock(mutex_);
  place_ = std::move(places);
  made_ = std::move(links);
  linked_ = framesLinked(place_);
  unsaved_.clear();
}

std::vector<PlaceLink> PlaceLinks::linksOfClosure(int frame, int reference) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const int place = placeOfLocked(reference);
  std::vector<PlaceLink> links;
  for (const PlaceLink& link : made_) {
    if (link.frame == frame && placeOfLocked(link.reference) == place) links.push_back(link);
  }
  return links;
}

void PlaceLinks::forget(const std::vector<PlaceLink>& forgotten) {
  const auto isForgotten = [&forgotten](const PlaceLink& link) {
    return std::any_of(forgotten.begin(), forgotten.end(), [&link](const PlaceLink& other) {
      return other.frame == link.frame && other.reference == link.reference;
    });
  };
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<PlaceLink> kept;
  kept.reserve(made_.size());
  std::copy_if(made_.begin(), made_.end(), std::back_inserter(kept),
               [&](const PlaceLink& link) { return !isForgotten(link); });
  // Links join places, so one cannot be taken out of place_ alone: the places are made again.
  std::vector<int> places = placesOf(kept, static_cast<int>(place_.size()));
  unsaved_.erase(std::remove_if(unsaved_.begin(), unsaved_.end(), isForgotten), unsaved_.end());
  place_ = std::move(places);
  made_ = std::move(kept);
  linked_ = framesLinked(place_);
}

std::vector<PlaceLink> PlaceLinks::asLinks(int frames) const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<PlaceLink> links;
  const int held = std::min(frames, static_cast<int>(place_.size()));
  for (int i = 0; i < held; ++i) {
    if (place_[static_cast<std::size_t>(i)] != i) links.push_back({i, place_[static_cast<std::size_t>(i)]});
  }
  return links;
}

void PlaceLinks::keepUnsaved() {
  std::lock_guard<std::mutex> lock(mutex_);
  keep_unsaved_ = true;
}

std::vector<PlaceLink> PlaceLinks::takeUnsaved() {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<PlaceLink> taken;
  taken.swap(unsaved_);
  return taken;
}

}  // namespace mrs_vpr
