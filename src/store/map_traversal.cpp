#include "mrs_vpr/store/map_traversal.hpp"

#include <algorithm>
#include <limits>

#include "mrs_vpr/number_text.hpp"

namespace mrs_vpr {

std::int64_t nextFrameNumber(std::int64_t last, const std::optional<MapTraversal>& map) {
  const std::int64_t next = last < std::numeric_limits<std::int64_t>::max() ? last + 1 : last;
  return map ? std::max(next, map->frames) : next;
}

void FrameNumbering::see(std::int64_t number) {
  largest_ = std::max(largest_, number < 0 ? seen_ : number);
  ++seen_;
}

std::int64_t FrameNumbering::next(const std::optional<MapTraversal>& map) const {
  return nextFrameNumber(largest_, map);
}

std::string keyframingMismatch(const std::optional<MapTraversal>& map, double min_appearance_change,
                               const std::string& setting) {
  if (!map || !map->min_appearance_change || *map->min_appearance_change == min_appearance_change) return "";
  return "the map's keyframes were kept at an appearance change of " + numberText(*map->min_appearance_change) +
         ", and " + setting + " is " + numberText(min_appearance_change) +
         ": test sequences then lie on another scale than the map's, which loses answers and can accept wrong ones";
}

}  // namespace mrs_vpr
