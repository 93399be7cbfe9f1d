#pragma once

#include <algorithm>
#include <vector>

namespace mrs_vpr {

/// Frames [begin, end): a test sequence of the map's own keyframes, the frames near an answer, or the
/// ends of a table of trajectory costs.
struct FrameRange {
  int begin = 0;
  int end = 0;

  int size() const { return end - begin; }
};

/// `ranges` sorted by their beginnings, those that overlap or touch joined into one.
inline std::vector<FrameRange> mergedRanges(std::vector<FrameRange> ranges) {
  std::sort(ranges.begin(), ranges.end(), [](const FrameRange& a, const FrameRange& b) { return a.begin < b.begin; });
  std::vector<FrameRange> merged;
  for (const FrameRange& range : ranges) {
    if (!merged.empty() && range.begin <= merged.back().end) {
      merged.back().end = std::max(merged.back().end, range.end);
    } else {
      merged.push_back(range);
    }
  }
  return merged;
}

}  // namespace mrs_vpr
