#pragma once

namespace mrs_vpr {

/// Map frames [begin, end): a test sequence of the map's own keyframes, or the frames near an answer.
struct FrameRange {
  int begin = 0;
  int end = 0;

  int size() const { return end - begin; }
};

}  // namespace mrs_vpr
