#include "drive_links.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <set>
#include <utility>
#include <vector>

#include "interruption.hpp"
#include "traversal_closures.hpp"

namespace mrs_vpr {
namespace tools {

namespace {

/// Where each drive begins: frame 0 and the map's recorded drive starts inside it, in order.
std::vector<int> driveBegins(const MapDatabase& map, int frames) {
  std::vector<int> begins{0};
  for (const int start : map.driveStarts()) {
    if (start > 0 && start < frames) begins.push_back(start);
  }
  std::sort(begins.begin(), begins.end());
  begins.erase(std::unique(begins.begin(), begins.end()), begins.end());
  return begins;
}

}  // namespace

DriveLinking linkDrives(MapDatabase& map, double min_appearance_change) {
  const std::int64_t count = map.size();
  const std::vector<int> begins = driveBegins(map, static_cast<int>(count));
  std::vector<PlaceLink> links = map.placeLinks(count);
  std::set<std::pair<int, int>> held;
  for (const PlaceLink& link : links) held.insert({link.frame, link.reference});
  std::vector<PlaceLink> added;
  TraversalClosures closures(map.descriptorParams(), min_appearance_change, 0);
  const auto keepNewLinks = [&] {
    for (const PlaceLink& link : closures.takeLinks()) {
      if (!held.insert({link.frame, link.reference}).second) continue;  // The map holds it already.
      links.push_back(link);
      added.push_back(link);
    }
  };
  // One pass over the frames: each drive is asked about as build_map asked when it added that drive,
  // knowing the earlier drives' links.
  closures.startTraversal({}, {});
  std::size_t next_drive = 1;
  int frame = 0;
  map.forEachFrame([&](const StoredFrame& stored) {
    if (next_drive < begins.size() && frame == begins[next_drive]) {
      keepNewLinks();
      std::vector<PlaceLink> earlier;
      std::copy_if(links.begin(), links.end(), std::back_inserter(earlier),
                   [&](const PlaceLink& link) { return link.frame < frame && link.reference < frame; });
      closures.startDrive(earlier);
      ++next_drive;
    }
    stopIfInterrupted();  // A large map takes a while: Ctrl-C leaves it as it was.
    closures.addKeyframe(stored.descriptor, stored.stamp);
    ++frame;
  });
  keepNewLinks();
  map.append({}, added);
  return {static_cast<int>(begins.size()), closures.questions(), closures.closures(), static_cast<int>(added.size())};
}

}  // namespace tools
}  // namespace mrs_vpr
