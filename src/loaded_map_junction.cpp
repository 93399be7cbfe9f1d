#include "mrs_vpr/loaded_map_junction.hpp"

#include <stdexcept>
#include <string>

#include "mrs_vpr/parameters.hpp"

namespace mrs_vpr {

void refuseSequenceAcrossLoadedMap(long long first, long long end, long long loaded_frames) {
  if (first < 0 || first >= loaded_frames || end <= loaded_frames) return;
  const long long frames = end - first;
  const long long added = end - loaded_frames;
  const std::string fewer =
      added >= kMinSequenceFrames ? ", or about at most " + std::to_string(added) + " now" : std::string();
  throw std::invalid_argument("a test sequence of " + std::to_string(frames) + " frames would join the loaded map's last " +
                              std::to_string(loaded_frames - first) + " frames to the " + std::to_string(added) +
                              " added since: two drives, whose junction is no place; ask again once " +
                              std::to_string(frames) + " frames have been added" + fewer);
}

}  // namespace mrs_vpr
