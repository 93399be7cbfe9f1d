#include "drive_links.hpp"

#include <algorithm>
#include <cstddef>
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
  std::vector<StoredFrame> frames;
  map.forEachFrame([&](const StoredFrame& frame) { frames.push_back({frame.descriptor.clone(), frame.stamp, "", -1}); });
  const int count = static_cast<int>(frames.size());
  // Drive d holds frames [bounds[d], bounds[d + 1]).
  std::vector<int> bounds = driveBegins(map, count);
  bounds.push_back(count);
  std::vector<PlaceLink> links = map.placeLinks(count);
  std::set<std::pair<int, int>> held;
  for (const PlaceLink& link : links) held.insert({link.frame, link.reference});
  std::vector<PlaceLink> added;
  DriveLinking result;
  for (std::size_t drive = 0; drive + 1 < bounds.size(); ++drive) {
    const int begin = bounds[drive];
    // The map as build_map held it when it added this drive: the earlier drives, their starts and links.
    TraversalClosures closures(map.descriptorParams(), min_appearance_change, begin);
    for (int i = 0; i < begin; ++i) closures.addMapFrame(frames[i].descriptor, frames[i].stamp);
    std::vector<PlaceLink> earlier;
    std::copy_if(links.begin(), links.end(), std::back_inserter(earlier),
                 [&](const PlaceLink& link) { return link.frame < begin && link.reference < begin; });
    const auto starts_end = bounds.begin() + std::max<std::ptrdiff_t>(1, static_cast<std::ptrdiff_t>(drive));
    closures.startTraversal(earlier, std::vector<int>(bounds.begin() + 1, starts_end));
    for (int i = begin; i < bounds[drive + 1]; ++i) {
      stopIfInterrupted();  // A large map takes a while: Ctrl-C leaves it as it was.
      closures.addKeyframe(frames[i].descriptor, frames[i].stamp);
    }
    for (const PlaceLink& link : closures.takeLinks()) {
      if (!held.insert({link.frame, link.reference}).second) continue;  // The map holds it already.
      links.push_back(link);
      added.push_back(link);
    }
    ++result.drives;
    result.questions += closures.questions();
    result.closures += closures.closures();
  }
  map.append({}, added);
  result.new_links = static_cast<int>(added.size());
  return result;
}

}  // namespace tools
}  // namespace mrs_vpr
